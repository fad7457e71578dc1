(** * The kernel's soundness: [decide I P W = Pass] implies that the profile,
    with Bayes beliefs, is a weak PBNE of the untruncated game of the
    instance (and that the witness's distances are the exact distances, so
    the game's terminal costs and the progress rule are the paper's).

    This covers every Defender the kernel decides: two goals with the
    progress rule or a table (default none, a constant or the progress
    rule), and N goals with a table (default none or a constant).  The
    proof assembles [KSound1]–[KSound3] with the abstract theorem
    [Pbne.pbne_of_checks] (TEL.4 and L3.1/L3.3, machine-proved). *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel Defender Pbne Potential Distances Kernel KFacts KSound1 KSound2 KSound3.
Open Scope Q_scope.

(** The profile's mixtures as the game's: (probability, the walk after [s0]). *)
Definition gamma (C : canon) (t : nat) : mixture nat :=
  map (fun e => (snd e, tl (fst e))) (nth t (mix C) []).

Lemma steps_firstn : forall (l : list nat) h u q,
  In q (steps nat h u l) <-> exists k, (1 <= k <= length l)%nat /\ q = rev (firstn k l) ++ u :: h.
Proof.
  induction l as [| v l IH]; intros h u q; simpl; split.
  - intros [].
  - intros [k [Hk _]]. lia.
  - intros [<- | Hin].
    + exists 1%nat. split; [lia | reflexivity].
    + apply IH in Hin as [k [Hk ->]]. exists (S k). split; [lia |].
      simpl. rewrite <- app_assoc. reflexivity.
  - intros [[| k] [Hk ->]]; [lia |]. destruct k as [| k].
    + left. reflexivity.
    + right. apply IH. exists (S k). split; [lia |]. simpl. rewrite <- app_assoc. reflexivity.
Qed.

Lemma firstn_length_le : forall (A : Type) (l : list A) k, length (firstn k l) = Nat.min k (length l).
Proof. intros. apply firstn_length. Qed.

(** A step of a walk is a prefix of it (reversed), of at least two nodes. *)
Lemma step_prefix : forall (s0 : nat) l q, (2 <= length q)%nat ->
  (In q (steps nat [] s0 l) <-> is_prefix (rev q) (s0 :: l) = true).
Proof.
  intros s0 l q Hq. rewrite steps_firstn. unfold is_prefix. rewrite leqb_eq. split.
  - intros [k [Hk ->]]. rewrite rev_app_distr, rev_involutive. simpl.
    rewrite firstn_length. replace (Nat.min k (length l)) with k by lia. reflexivity.
  - intros H. rewrite rev_length in H. destruct (length q) as [| m] eqn:Hm; [lia |].
    simpl in H. exists m.
    assert (Hl : length (rev q) = length (s0 :: firstn m l)) by (rewrite H; reflexivity).
    rewrite rev_length, Hm in Hl. simpl in Hl. rewrite firstn_length in Hl.
    split; [lia |]. rewrite <- (rev_involutive q), H. simpl. reflexivity.
Qed.

Lemma qmax_ge : forall l x, In x l -> x <= qmax l.
Proof.
  induction l as [| y l IH]; intros x Hx; [destruct Hx |]. simpl. unfold qmax2.
  destruct (Qle_bool y (qmax l)) eqn:E; destruct Hx as [-> | Hx].
  - apply Qle_bool_iff. exact E.
  - exact (IH x Hx).
  - lra.
  - pose proof (IH x Hx). assert (Hn : ~ (y <= qmax l)) by (intros Hc; apply Qle_bool_iff in Hc; congruence).
    apply Qnot_le_lt in Hn. lra.
Qed.

Section Final.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Hypothesis Hi : instance_ok I = true.
  Hypothesis Hshape : dist_shape_ok I W = true.
  Hypothesis Hdist : distances_ok I W = true.
  Hypothesis Hreach : reach_ok I W = true.
  Hypothesis Hmixlen : length (mix C) = N I.
  Hypothesis Hmix : forall m, In m (mix C) -> mixture_ok I m = true.
  Hypothesis Hrule : rule_ok I (crule C).
  Variables (es : list (list nat * list Q)) (dflt : default) (gl : nat).
  Hypothesis Hcr : crule C = RTable es dflt gl.
  Hypothesis Hdef : forallb (walk_defined I W C) (all_walks C) = true.
  Hypothesis Hgreedy : greedy_ok I W C = true.

  Notation E := (fun a b => has_arc I a b = true).
  Notation dfd := (defender I W C).

  Lemma mix_in : forall t, (t < N I)%nat -> In (nth t (mix C) []) (mix C).
  Proof. intros t Ht. apply nth_In. lia. Qed.

  Lemma mix_walk0 : forall t e, (t < N I)%nat -> In e (nth t (mix C) []) ->
    0 <= snd e /\ exists l, fst e = start I :: l /\ gwalk nat E (isgoal I) (start I) l.
  Proof.
    intros t e Ht He. pose proof (Hmix _ (mix_in t Ht)) as Hm.
    unfold mixture_ok in Hm. repeat rewrite andb_true_iff in Hm. destruct Hm as [[[_ Hall] _] _].
    rewrite forallb_forall in Hall. specialize (Hall e He). apply andb_true_iff in Hall as [Hp Hw].
    apply Qle_bool_iff in Hp. split; [exact Hp |].
    destruct (walk_ok_true I _ Hw) as [l [Hl [Hg _]]]. exists l. auto.
  Qed.

  Lemma mix_walk : forall t e, (t < N I)%nat -> In e (nth t (mix C) []) ->
    0 <= snd e /\ exists l, fst e = start I :: l /\ gwalk nat E (isgoal I) (start I) l /\
                            walk_defined I W C (fst e) = true.
  Proof.
    intros t e Ht He. destruct (mix_walk0 t e Ht He) as [Hp [l [Hl Hg]]].
    split; [exact Hp |]. exists l. split; [exact Hl | split; [exact Hg |]].
    unfold all_walks in Hdef. rewrite forallb_forall in Hdef. apply Hdef.
    apply in_flat_map. exists (nth t (mix C) []). split; [exact (mix_in t Ht) | apply in_map; exact He].
  Qed.

  Lemma gamma_valid : forall t, In t (types I) -> valid_mixture nat E (isgoal I) (start I) (gamma C t).
  Proof.
    intros t Ht. unfold types in Ht. apply in_seq in Ht. split.
    - unfold gamma. rewrite sumL_map. simpl.
      pose proof (Hmix _ (mix_in t ltac:(lia))) as Hm. unfold mixture_ok in Hm.
      apply andb_true_iff in Hm as [_ Hs]. apply Qeq_bool_iff in Hs. rewrite <- Hs, qsum_sumL. reflexivity.
    - intros p l Hin. unfold gamma in Hin. apply in_map_iff in Hin as [e [Heq He]]. inversion Heq; subst.
      destruct (mix_walk0 t e ltac:(lia) He) as [Hp [l [Hl Hg]]]. rewrite Hl. simpl. auto.
  Qed.

  (** The kernel's costs along the profile's walks are the game's. *)
  Lemma J_wcost : forall t l h u, defined_along I W C (rev (u :: h)) l = true ->
    J nat nat (wt I) (Dv W) t dfd h u l == wcost I W C t (rev (u :: h)) l.
  Proof.
    intros t. induction l as [| v l IH]; intros h u Hd.
    - cbn [J wcost]. rewrite last_rev_cons. reflexivity.
    - cbn [J wcost]. cbn [defined_along] in Hd.
      destruct (sigma I W C (rev (u :: h)) v) as [q |] eqn:Hs; [| discriminate].
      change (rev (u :: h) ++ [v]) with (rev (v :: u :: h)) in *.
      rewrite (IH (u :: h) v Hd). unfold defender. rewrite (gsig_defined I W C _ _ t q Hs), last_rev_cons.
      reflexivity.
  Qed.

  Lemma U_Umix : forall t, (t < N I)%nat ->
    Umix nat (types I) nat (wt I) (Dv W) (start I) t (of_w nat nat dfd) (gamma C t) == U I W C t.
  Proof.
    intros t Ht.
    rewrite (Umix_of_w nat (types I) nat (wt I) (Dv W) (start I) t dfd (gamma C t)
               (defender_dist I W C Hi Hshape Hdist Hrule es dflt gl Hcr)).
    unfold U, gamma. rewrite qsum_sumL, sumL_map. apply sumL_ext. intros e He. simpl.
    destruct (mix_walk t e Ht He) as [_ [l [Hl [_ Hd]]]].
    unfold walk_cost, walk_defined in *. rewrite Hl in *. simpl in *.
    rewrite (J_wcost t l [] (start I) Hd). reflexivity.
  Qed.

  (** The Defender check in the game's terms. *)
  Lemma mass_eq : forall t q, (2 <= length q)%nat ->
    Game.mass nat nat Nat.eq_dec (start I) (priorq I) (gamma C) t q == Kernel.mass I C t (rev q).
  Proof.
    intros t q Hq. unfold Game.mass, Kernel.mass, reach, gamma.
    apply Qmult_comp; [reflexivity |]. rewrite qsum_sumL, sumL_map. apply sumL_ext. intros e He. simpl.
    destruct (Nat.lt_ge_cases t (N I)) as [Ht | Ht].
    2: { rewrite nth_overflow in He by lia. destruct He. }
    destruct (mix_walk0 t e Ht He) as [_ [l [Hl _]]]. rewrite Hl. simpl tl.
    unfold visits. destruct (in_dec (list_eq_dec Nat.eq_dec) q (steps nat [] (start I) l)) as [Hin | Hnin].
    - apply (step_prefix (start I) l q Hq) in Hin. rewrite Hin. ring.
    - destruct (is_prefix (rev q) (start I :: l)) eqn:Hp; [| ring].
      exfalso. apply Hnin. apply (step_prefix (start I) l q Hq). exact Hp.
  Qed.

  Lemma defined_prefix : forall l p k, defined_along I W C p l = true -> (k < length l)%nat ->
    exists q, sigma I W C (p ++ firstn k l) (nth k l O) = Some q.
  Proof.
    induction l as [| v l IH]; intros p k Hd Hk; simpl in *; [lia |].
    destruct (sigma I W C p v) as [q |] eqn:Hs; [| discriminate].
    destruct k as [| k]; [exists q; rewrite app_nil_r; exact Hs |].
    destruct (IH (p ++ [v]) k Hd ltac:(lia)) as [q' Hq']. exists q'.
    simpl. rewrite <- app_assoc in Hq'. exact Hq'.
  Qed.

  Theorem kernel_greedy : forall q, on_path nat (types I) nat Nat.eq_dec (start I) (priorq I) (gamma C) q ->
    greedy nat (types I) nat Nat.eq_dec (start I) (priorq I) (gamma C) dfd q.
  Proof.
    intros q Hon.
    destruct (on_path_step nat (types I) nat Nat.eq_dec (start I) (priorq I) (prior_nonneg I Hi) (gamma C) q Hon)
      as [t0 [p0 [l0 [Ht0 [Hpl0 Hq0]]]]].
    unfold gamma in Hpl0. apply in_map_iff in Hpl0 as [e0 [He0 Hin0]]. inversion He0; subst p0 l0.
    unfold types in Ht0. apply in_seq in Ht0.
    destruct (mix_walk t0 e0 ltac:(lia) Hin0) as [_ [l [Hl [_ Hd]]]]. rewrite Hl in Hq0. simpl tl in Hq0.
    destruct (proj1 (steps_firstn l [] (start I) q) Hq0) as [k [Hk Hqk]].
    assert (Hq2 : (2 <= length q)%nat) by (rewrite Hqk, app_length, rev_length, firstn_length; simpl; lia).
    assert (Hpre := proj1 (step_prefix (start I) l q Hq2) Hq0).
    (* the shape q = v :: u :: h *)
    destruct q as [| v [| u h]]; [simpl in Hq2; lia | simpl in Hq2; lia |].
    (* rev q is in the kernel's mass trie *)
    assert (HM : In (rev (v :: u :: h)) (mass_trie C)).
    { unfold mass_trie. apply add_new_In. right. apply in_flat_map. exists (fst e0). split.
      - unfold all_walks. apply in_flat_map. exists (nth t0 (mix C) []). split; [apply mix_in; lia | apply in_map; exact Hin0].
      - apply in_prefixes. unfold is_prefix in Hpre. apply leqb_eq in Hpre. rewrite Hl.
        exists (length (rev (v :: u :: h))). split.
        + rewrite rev_length. simpl. simpl in Hqk.
          apply (f_equal (@length nat)) in Hqk. rewrite !app_length, rev_length, firstn_length in Hqk. simpl in *. lia.
        + exact Hpre. }
    unfold greedy_ok in Hgreedy. rewrite forallb_forall in Hgreedy. specialize (Hgreedy _ HM).
    unfold greedy_at in Hgreedy. rewrite forallb_forall in Hgreedy.
    change (rev (v :: u :: h)) with (rev (u :: h) ++ [v]) in Hgreedy.
    rewrite removelast_app1, last_app1 in Hgreedy.
    (* σ is defined at this prefix *)
    assert (Hs : exists qq, sigma I W C (rev (u :: h)) v = Some qq).
    { unfold walk_defined in Hd. rewrite Hl in Hd. simpl in Hd.
      assert (Hk1 : (k - 1 < length l)%nat) by lia.
      destruct (defined_prefix l [start I] (k - 1) Hd Hk1) as [qq Hqq]. exists qq.
      assert (Hrev : rev (v :: u :: h) = start I :: firstn k l).
      { rewrite Hqk. rewrite rev_app_distr, rev_involutive. reflexivity. }
      replace k with (S (k - 1)) in Hrev by lia.
      rewrite (firstn_snoc l (k - 1) Hk1) in Hrev.
      change (rev (v :: u :: h)) with (rev (u :: h) ++ [v]) in Hrev.
      rewrite app_comm_cons in Hrev. apply app_inj_tail in Hrev as [Hp Hv].
      rewrite Hp, Hv. simpl in Hqq. exact Hqq. }
    destruct Hs as [qq Hs].
    intros t t' Ht Ht' Hpos. unfold sig_at, of_w, defender in Hpos. cbv beta in Hpos.
    rewrite (gsig_defined I W C _ _ t qq Hs) in Hpos.
    rewrite !mass_eq by (simpl; lia).
    change (rev (v :: u :: h)) with (rev (u :: h) ++ [v]).
    specialize (Hgreedy t Ht). apply negb_true_iff in Hgreedy.
    assert (Htop : 0 < qmax (map (fun t => Kernel.mass I C t (rev (u :: h) ++ [v])) (types I))).
    { unfold on_path, Game.Z in Hon. destruct (sum_pos nat _ _ Hon) as [t1 [Ht1 Hm1]].
      rewrite mass_eq in Hm1 by (simpl; lia).
      change (rev (v :: u :: h)) with (rev (u :: h) ++ [v]) in Hm1.
      pose proof (qmax_ge _ _ (in_map (fun t => Kernel.mass I C t (rev (u :: h) ++ [v])) _ _ Ht1)). lra. }
    apply ltb_lt in Htop. apply ltb_lt in Hpos. rewrite Htop, Hpos in Hgreedy. rewrite !andb_true_l in Hgreedy.
    apply ltb_false in Hgreedy.
    pose proof (qmax_ge _ _ (in_map (fun t => Kernel.mass I C t (rev (u :: h) ++ [v])) _ _ Ht')). lra.
  Qed.
End Final.

(** ** What [decide = Pass] says, check by check. *)
Lemma check_type_not_pass : forall I W C t r, check_type I W C t r <> Some Pass.
Proof.
  intros I W C t r H. unfold check_type in H. cbv zeta in H.
  repeat match type of H with
  | context [if ?c then _ else _] => destruct c
  | context [match ?c with _ => _ end] => destruct c
  end; discriminate.
Qed.

Lemma check_types_not_pass : forall I W C rs t, check_types I W C t rs <> Some Pass.
Proof.
  intros I W C. induction rs as [| r rs IH]; intros t H; cbn [check_types] in H; [discriminate |].
  destruct (check_type I W C t r) eqn:E; [inversion H; subst; exact (check_type_not_pass I W C t r E) |].
  exact (IH _ H).
Qed.

Lemma counter_not_pass : forall I W C l, first_some (counter_ok I W C) l <> Some Pass.
Proof.
  intros I W C. induction l as [| [t w] l IH]; intros H; cbn [first_some] in H; [discriminate |].
  destruct (counter_ok I W C (t, w)) eqn:E.
  - inversion H; subst. unfold counter_ok in E.
    repeat match type of E with context [if ?c then _ else _] => destruct c end; discriminate.
  - exact (IH H).
Qed.

Lemma check_types_all : forall I W C rs k, check_types I W C k rs = None ->
  forall i, (i < length rs)%nat -> check_type I W C (k + i) (nth i rs (mkType false None None None None)) = None.
Proof.
  intros I W C. induction rs as [| r rs IH]; intros k H i Hi; simpl in *; [lia |].
  destruct (check_type I W C k r) eqn:E; [discriminate |].
  destruct i as [| i]; [rewrite Nat.add_0_r; exact E |].
  replace (k + S i)%nat with (S k + i)%nat by lia. apply IH; [exact H | lia].
Qed.

Lemma decide_read : forall I P W, decide I P W = Pass ->
  instance_ok I = true /\ exists C, read_profile I P = Some C.
Proof.
  intros I P W H. unfold decide in H.
  destruct (instance_ok I); [| discriminate]. split; [reflexivity |].
  destruct (read_profile I P) as [C |]; [exists C; reflexivity | discriminate].
Qed.

Lemma decide_spec : forall I P W C es dflt gl, decide I P W = Pass -> read_profile I P = Some C ->
  crule C = RTable es dflt gl ->
  exists rs,
    instance_ok I = true /\ dist_shape_ok I W = true /\
    distances_ok I W = true /\ reach_ok I W = true /\
    forallb (walk_defined I W C) (all_walks C) = true /\ greedy_ok I W C = true /\
    wtypes W = Some rs /\ length rs = N I /\ check_types I W C O rs = None.
Proof.
  intros I P W C es dflt gl H H2 H6. unfold decide in H.
  destruct (instance_ok I) eqn:H1; [| discriminate]. simpl in H. rewrite H2 in H.
  destruct (Z.ltb 0 (denominator W)); [| discriminate]. simpl in H.
  destruct (dist_shape_ok I W) eqn:H3; [| discriminate]. simpl in H.
  destruct (distances_ok I W) eqn:H4; [| discriminate]. simpl in H.
  destruct (reach_ok I W) eqn:H5; [| discriminate]. simpl in H.
  rewrite H6 in H.
  destruct (match wguarantee W with Some _ => true | None => false end); [discriminate |].
  destruct (forallb (walk_defined I W C) (all_walks C)) eqn:H7; [| discriminate]. simpl in H.
  destruct (greedy_ok I W C) eqn:H8; [| discriminate]. simpl in H.
  destruct (first_some (counter_ok I W C) (counterexamples W)) eqn:H9.
  { subst. exfalso. exact (counter_not_pass I W C _ H9). }
  destruct (wtypes W) as [rs |] eqn:H10; [| discriminate].
  destruct (Nat.eqb (length rs) (N I)) eqn:H11; [| discriminate]. simpl in H.
  destruct (check_types I W C O rs) eqn:H12.
  { subst. exfalso. exact (check_types_not_pass I W C rs O H12). }
  exists rs. apply Nat.eqb_eq in H11. repeat split; assumption.
Qed.

(** ** The soundness theorem of the kernel, for table Defenders (the progress
    rule is the empty table with the progress default). *)
Theorem kernel_sound : forall I P W C es dflt gl, decide I P W = Pass ->
  read_profile I P = Some C -> crule C = RTable es dflt gl ->
    (forall j v, (j < N I)%nat -> (v < n I)%nat -> is_distance (adj I) (goal I j) v (D W j v)) /\
    weak_pbne nat Nat.eq_dec (types I) nat Nat.eq_dec (fun a b => has_arc I a b = true) (wt I)
              (isgoal I) (Dv W) (start I) (priorq I) (gamma C) (of_w nat nat (defender I W C))
              (bayes nat (types I) nat Nat.eq_dec (start I) (priorq I) (gamma C)).
Proof.
  intros I P W C es dflt gl H Hc Hcr.
  destruct (decide_spec I P W C es dflt gl H Hc Hcr)
    as [rs [Hi [Hshape [Hdist [Hreach [Hdef [Hgr [Hrs [Hlen Hts]]]]]]]]].
  destruct (read_profile_spec I Hi P C Hc) as [Hmixlen [Hmix Hrule]].
  split; [exact (distances_exact I W Hi Hdist) |].
  apply pbne_of_checks.
  - unfold types. apply seq_NoDup.
  - intros u v Huv. exact (wt_nonneg I Hi u v Huv).
  - exact (Dv_nonneg I W Hi Hshape Hdist).
  - exact (prior_nonneg I Hi).
  - exact (defender_dist I W C Hi Hshape Hdist Hrule es dflt gl Hcr).
  - eapply gamma_valid; eassumption.
  - intros t Ht l Hl. unfold types in Ht. apply in_seq in Ht.
    erewrite U_Umix; eauto; [| lia].
    pose proof (check_types_all I W C rs O Hts t ltac:(lia)) as Hct. simpl in Hct.
    destruct (check_type_spec I W C t _ Hct) as [xs [e [He [Htrie HU]]]].
    exact (attacker_bound I W C Hi Hdist Hreach Hrule es dflt gl Hcr t ltac:(lia) xs e He Htrie HU l Hl).
  - eapply kernel_greedy; eassumption.
Qed.

(** The Bayesian Nash condition (5a) for the Defender, at the root, too. *)
Corollary kernel_defender_optimal : forall I P W C es dflt gl, decide I P W = Pass ->
  read_profile I P = Some C -> crule C = RTable es dflt gl ->
    defender_optimal nat (types I) nat (wt I) (Dv W) (start I) (priorq I) (gamma C) (of_w nat nat (defender I W C)).
Proof.
  intros I P W C es dflt gl H Hc Hcr.
  destruct (decide_spec I P W C es dflt gl H Hc Hcr) as [rs [Hi [Hshape [Hdist [Hreach [Hdef [Hgr _]]]]]]].
  destruct (read_profile_spec I Hi P C Hc) as [Hmixlen [Hmix Hrule]].
  apply (defender_optimal_of_checks nat (types I) nat Nat.eq_dec (fun a b => has_arc I a b = true) (wt I)
           (isgoal I) (Dv W) (start I) (priorq I) (fun u v Huv => wt_nonneg I Hi u v Huv) (prior_nonneg I Hi)
           (gamma C)).
  - exact (defender_dist I W C Hi Hshape Hdist Hrule es dflt gl Hcr).
  - eapply gamma_valid; eassumption.
  - eapply kernel_greedy; eassumption.
Qed.
