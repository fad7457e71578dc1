(** * Soundness of the kernel's guarantee-rule branch (K.7), modulo NR.2.

    [decide = Pass] for a guarantee-rule profile implies: the witness's σ at
    every prefix of the profile's walks is the lexicographic minimum of the
    rule's set F at the rule's state (the stage duals, [step_ok_lexmin]), the
    kernel's costs and masses are the game's, and the kernel's arc test gives
    the arc condition in the form NR.2 uses (the cover bound).  With NR.2 as
    an explicit hypothesis, every Defender that follows the rule is then part
    of a weak PBNE ([kernel_sound_guarantee]). *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith Permutation.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel Defender Pbne Potential Distances Kernel KFacts
  KSound1 KSound2 KSound3 KSound Guarantee.
Open Scope Q_scope.

(** ** Dot products over lists. *)
Lemma dotq_cons : forall x a y b, dotq (x :: a) (y :: b) = x * y + dotq a b.
Proof. reflexivity. Qed.

Lemma dotq_sum : forall a b,
  dotq a b == sumL (fun i => nth i a 0 * nth i b 0) (seq 0 (Nat.min (length a) (length b))).
Proof.
  induction a as [| x a IH]; intros [| y b]; simpl; try reflexivity.
  rewrite dotq_cons, IH, <- seq_shift, sumL_map. reflexivity.
Qed.

Lemma dotq_dotv : forall N a b, length a = N -> length b = N ->
  dotq a b == dotv N a (fun i => nth i b 0).
Proof. intros N a b Ha Hb. rewrite dotq_sum, Ha, Hb, Nat.min_id. reflexivity. Qed.

Lemma nums_k_len : forall x k l, nums_k x k = Some l -> length l = k.
Proof.
  intros [| xs] k l H; simpl in H; [discriminate |].
  destruct (Nat.eqb (length xs) k) eqn:E; [| discriminate]. apply Nat.eqb_eq in E. subst k.
  revert l H. induction xs as [| [x |] xs IH]; intros l H; simpl in *; [inversion H; reflexivity | |discriminate].
  destruct (all_some xs) as [l' |] eqn:E'; simpl in H; [| discriminate]. inversion H; subst. simpl.
  f_equal. apply IH. reflexivity.
Qed.

Lemma all_some_len : forall (A : Type) (l : list (option A)) l', all_some l = Some l' -> length l' = length l.
Proof.
  intros A. induction l as [| [x |] l IH]; intros l' H; simpl in *; [inversion H; reflexivity | | discriminate].
  destruct (all_some l) as [l0 |] eqn:E; simpl in H; [| discriminate]. inversion H; subst. simpl.
  f_equal. apply IH. reflexivity.
Qed.

Lemma all_some_nth : forall (A : Type) (l : list (option A)) l' i d, all_some l = Some l' -> (i < length l)%nat ->
  nth i l None = Some (nth i l' d).
Proof.
  intros A. induction l as [| [x |] l IH]; intros l' i d H Hi; simpl in *; [lia | | discriminate].
  destruct (all_some l) as [l0 |] eqn:E; simpl in H; [| discriminate]. inversion H; subst.
  destruct i as [| i]; [reflexivity |]. simpl. apply IH; [reflexivity | lia].
Qed.

Lemma nth_map_lt : forall (A B : Type) (f : A -> B) l i da db, (i < length l)%nat ->
  nth i (map f l) db = f (nth i l da).
Proof.
  intros A B f l i da db Hi. rewrite (nth_indep (map f l) db (f da)) by (rewrite map_length; exact Hi).
  apply map_nth.
Qed.

(** ** The priority order is a permutation of the types. *)
Lemma insert_by_perm : forall I t l, Permutation (insert_by I t l) (t :: l).
Proof.
  intros I t. induction l as [| x l IH]; simpl; [reflexivity |].
  destruct (ltb (priorq I x) (priorq I t) || (Qeq_bool (priorq I x) (priorq I t) && Nat.ltb t x)).
  - reflexivity.
  - eapply perm_trans; [apply perm_skip, IH | apply perm_swap].
Qed.

Lemma order_perm : forall I, Permutation (order I) (types I).
Proof.
  intros I. unfold order.
  enough (H : forall l, Permutation (fold_right (insert_by I) [] l) l).
  { eapply perm_trans; [apply H |]. apply Permutation_sym, Permutation_rev. }
  induction l as [| x l IH]; simpl; [reflexivity |].
  eapply perm_trans; [apply insert_by_perm | apply perm_skip, IH].
Qed.

Section Step.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Notation A := (normals I C).
  Notation o := (order I).
  Hypothesis A_len : forall a, In a A -> length a = N I.

  Lemma order_len : length o = N I.
  Proof. rewrite (Permutation_length (order_perm I)). apply seq_length. Qed.

  Lemma stages_spec : forall sg beta ds k, stages I A o sg beta k ds = None ->
    forall j, (j < length ds)%nat -> exists y fx z,
      nums_k (dy (nth j ds (mkDual NBad NBad None))) (length A) = Some y /\
      nums_k (dfix (nth j ds (mkDual NBad NBad None))) (k + j) = Some fx /\
      dz (nth j ds (mkDual NBad NBad None)) = Some z /\ stage_holds I A o sg beta (k + j) y fx z = true.
  Proof.
    intros sg beta. induction ds as [| d ds IH]; intros k H j Hj; simpl in *; [lia |].
    destruct (nums_k (dy d) (length A)) as [y |] eqn:Ey; [| discriminate].
    destruct (nums_k (dfix d) k) as [fx |] eqn:Ef; [| discriminate].
    destruct (dz d) as [z |] eqn:Ez; [| discriminate].
    destruct (stage_holds I A o sg beta k y fx z) eqn:Eh; [| discriminate].
    destruct j as [| j].
    - exists y, fx, z. rewrite Nat.add_0_r. auto.
    - destruct (IH (S k) H j ltac:(lia)) as [y' [fx' [z' [H1 [H2 [H3 H4]]]]]].
      exists y', fx', z'. replace (k + S j)%nat with (S k + j)%nat by lia. auto.
  Qed.

  Lemma stage_dual : forall sg beta k y fx z, (k < N I)%nat -> length y = length A -> length fx = k ->
    length beta = length A -> length sg = N I ->
    stage_holds I A o sg beta k y fx z = true ->
    dual_ok (N I) A (fun a => nth a beta 0) o (fun i => nth i sg 0) k y z fx.
  Proof.
    intros sg beta k y fx z Hk Hy Hfx Hb Hsg H. unfold stage_holds in H.
    repeat rewrite andb_true_iff in H. destruct H as [[H0 Hc] Hobj].
    rewrite forallb_forall in H0, Hc. pose proof order_len as Hol. split; [| split].
    - intros a Ha. apply Qle_bool_iff, H0, nth_In. lia.
    - intros i Hi. specialize (Hc i Hi). apply Qle_bool_iff in Hc. unfold coef, ind, ord.
      rewrite !dotq_sum in Hc. rewrite Hy, map_length, Nat.min_id, Hfx, map_length in Hc.
      replace (Nat.min k (length o)) with k in Hc by lia.
      rewrite (sumL_ext (fun a => nth a y 0 * nth i (nth a A []) 0)
                        (fun a => nth a y 0 * nth a (map (fun a0 => nth i a0 0) A) 0)).
      2: { intros a Ha. apply in_seq in Ha. rewrite (nth_map_lt _ _ _ A a [] 0) by lia. reflexivity. }
      rewrite (sumL_ext (fun j => nth j fx 0 * (if Nat.eq_dec i (nth j o O) then 1 else 0))
                        (fun j => nth j fx 0 * nth j (map (fun j0 => if Nat.eqb j0 i then 1 else 0) o) 0)).
      2: { intros j Hj. apply in_seq in Hj. rewrite (nth_map_lt _ _ _ o j O 0) by lia.
           destruct (Nat.eq_dec i (nth j o O)) as [-> | Hne]; [rewrite Nat.eqb_refl; reflexivity |].
           destruct (Nat.eqb (nth j o O) i) eqn:E; [apply Nat.eqb_eq in E; congruence | reflexivity]. }
      destruct (Nat.eq_dec i (nth k o O)) as [-> | Hne].
      + rewrite Nat.eqb_refl in Hc. exact Hc.
      + destruct (Nat.eqb i (nth k o O)) eqn:E; [apply Nat.eqb_eq in E; contradiction | exact Hc].
    - apply Qle_bool_iff in Hobj. unfold ord. rewrite !dotq_sum in Hobj.
      rewrite Hy, Hb, Nat.min_id, Hfx, map_length in Hobj.
      replace (Nat.min k (length o)) with k in Hobj by lia.
      rewrite (sumL_ext (fun j => nth j fx 0 * nth (nth j o O) sg 0)
                        (fun j => nth j fx 0 * nth j (map (fun j0 => nth j0 sg 0) o) 0)); [exact Hobj |].
      intros j Hj. apply in_seq in Hj. rewrite (nth_map_lt _ _ _ o j O 0) by lia. reflexivity.
  Qed.

  (** [step_ok_lexmin]: a σ the kernel accepts at a prefix is the rule's
      lexicographic minimum of F at that state. *)
  Theorem step_ok_lexmin : forall m rec r u wt0 sg, length r = N I ->
    step_ok I C m rec r u wt0 = inr sg ->
    exists mu, all_some (map (fun i => get (nth i m []) u) (seq 0 (length A))) = Some mu /\
      length sg = N I /\
      lexmin (N I) A (fun k => (dotq (nth k A []) r - nth k mu 0) / wt0) o (fun i => nth i sg 0).
  Proof.
    intros m rec r u wt0 sg Hr H. unfold step_ok in H.
    destruct (nums_k (ssigma rec) (N I)) as [sg0 |] eqn:Es; [| discriminate].
    destruct (sduals rec) as [duals |] eqn:Ed; [| discriminate].
    destruct (negb (Nat.eqb (length duals) (N I - 1))) eqn:El; [discriminate |].
    apply negb_false_iff, Nat.eqb_eq in El.
    destruct (all_some (map (fun i => get (nth i m []) u) (seq 0 (length A)))) as [mu |] eqn:Em; [| discriminate].
    set (betal := map (fun i => (dotq (nth i A []) r - nth i mu 0) / wt0) (seq 0 (length A))) in H.
    match type of H with (if ?c then _ else _) = _ => destruct c eqn:Ep end; [discriminate |].
    destruct (stages I A o sg0 betal O duals) eqn:Est; [discriminate |]. inversion H; subst sg0. clear H.
    exists mu. pose proof (nums_k_len _ _ _ Es) as Hsl. split; [reflexivity | split; [exact Hsl |]].
    apply negb_false_iff in Ep. repeat rewrite andb_true_iff in Ep. destruct Ep as [[Hnn Hsum] HF].
    rewrite forallb_forall in Hnn, HF. apply Qeq_bool_iff in Hsum.
    assert (Hbeta : forall k, (k < length A)%nat -> nth k betal 0 == (dotq (nth k A []) r - nth k mu 0) / wt0).
    { intros k Hk. unfold betal. rewrite (nth_map_lt _ _ _ (seq 0 (length A)) k O 0) by (rewrite seq_length; exact Hk).
      rewrite seq_nth by exact Hk. reflexivity. }
    apply (lexmin_ext _ _ (fun k => nth k betal 0)).
    { intros k. destruct (Nat.lt_ge_cases k (length A)) as [Hk | Hk]; [apply Hbeta, Hk |].
      unfold betal. rewrite nth_overflow by (rewrite map_length, seq_length; exact Hk).
      rewrite (nth_overflow A) by exact Hk. rewrite (nth_overflow mu); [change (dotq [] r) with 0; unfold Qdiv; ring |].
      rewrite (all_some_len _ _ _ Em), map_length, seq_length. exact Hk. }
    apply (lexmin_of_certificate (N I) A _ o (order_perm I) _
             (fun k => match nums_k (dy (nth k duals (mkDual NBad NBad None))) (length A),
                            nums_k (dfix (nth k duals (mkDual NBad NBad None))) k,
                            dz (nth k duals (mkDual NBad NBad None)) with
                       | Some y, Some fx, Some z => (y, z, fx)
                       | _, _, _ => ([], 0, [])
                       end)).
    - split; [| split].
      + intros i Hi. apply in_seq in Hi. apply Qle_bool_iff, Hnn, nth_In. lia.
      + unfold types. rewrite <- Hsl, sumL_nth_seq. exact Hsum.
      + intros k Hk. specialize (HF k (proj2 (in_seq _ _ _) (conj (Nat.le_0_l k) Hk))).
        apply Qle_bool_iff in HF. rewrite <- dotq_dotv; [exact HF | apply A_len, nth_In, Hk | exact Hsl].
    - intros k Hk. destruct (stages_spec sg betal duals O Est k ltac:(lia)) as [y [fx [z [Hy [Hfx [Hz Hh]]]]]].
      simpl in Hfx. rewrite Hy, Hfx, Hz.
      apply stage_dual; [lia | exact (nums_k_len _ _ _ Hy) | exact (nums_k_len _ _ _ Hfx) | | exact Hsl | exact Hh].
      unfold betal. rewrite map_length, seq_length. reflexivity.
  Qed.
End Step.

(** ** The mass trie: duplicate-free, parents first. *)
Definition parents_first (L : list (list nat)) : Prop :=
  forall i, (i < length L)%nat -> (3 <= length (nth i L []))%nat ->
    exists j, (j < i)%nat /\ nth j L [] = removelast (nth i L []).

Lemma add_new_nodup : forall acc p, NoDup acc -> NoDup (add_new acc p).
Proof.
  intros acc p H. unfold add_new. destruct (memb p acc) eqn:E; [exact H |].
  apply (Permutation_NoDup (l := p :: acc)); [apply Permutation_cons_append |].
  constructor; [| exact H]. intros Hin. apply memb_In in Hin. congruence.
Qed.

Lemma add_new_pf : forall acc p, parents_first acc ->
  ((3 <= length p)%nat -> In (removelast p) acc) -> parents_first (add_new acc p).
Proof.
  intros acc p H Hp. unfold add_new. destruct (memb p acc); [exact H |].
  intros i Hi Hl. rewrite app_length in Hi. simpl in Hi.
  destruct (Nat.lt_ge_cases i (length acc)) as [Hlt | Hge].
  - rewrite app_nth1 in Hl |- * by exact Hlt.
    destruct (H i Hlt Hl) as [j [Hj Heq]]. exists j. split; [exact Hj |].
    rewrite app_nth1 by lia. exact Heq.
  - assert (i = length acc) by lia. subst i. rewrite app_nth2 in Hl |- * by lia.
    rewrite Nat.sub_diag in Hl |- *. simpl in *.
    destruct (In_nth _ _ [] (Hp Hl)) as [j [Hj Heq]]. exists j. split; [exact Hj |].
    rewrite app_nth1 by exact Hj. exact Heq.
Qed.

Lemma fold_prefixes : forall w acc, NoDup acc -> parents_first acc ->
  NoDup (fold_left add_new (prefixes w) acc) /\ parents_first (fold_left add_new (prefixes w) acc) /\
  (forall x, In x acc -> In x (fold_left add_new (prefixes w) acc)).
Proof.
  intros w acc Hnd Hpf. unfold prefixes.
  assert (Hgen : forall m, (m <= length w - 1)%nat ->
    let R := fold_left add_new (map (fun k => firstn k w) (seq 2 m)) acc in
    NoDup R /\ parents_first R /\ (forall x, In x acc -> In x R) /\
    (forall k, (2 <= k < 2 + m)%nat -> In (firstn k w) R)).
  { induction m as [| m IH]; intros Hm R; subst R.
    - simpl. split; [exact Hnd | split; [exact Hpf | split; [auto | intros k Hk; lia]]].
    - rewrite seq_S, map_app, fold_left_app. cbn [fold_left map].
      destruct (IH ltac:(lia)) as [H1 [H2 [H3 H4]]].
      set (R := fold_left add_new (map (fun k => firstn k w) (seq 2 m)) acc) in *.
      assert (Hmem : forall x, In x R -> In x (add_new R (firstn (2 + m) w))).
      { intros x Hx. unfold add_new. destruct (memb _ R); [exact Hx | apply in_or_app; left; exact Hx]. }
      split; [apply add_new_nodup, H1 |]. split; [| split; [intros x Hx; apply Hmem, H3, Hx |]].
      + apply add_new_pf; [exact H2 |]. intros Hl.
        rewrite firstn_length in Hl.
        replace (2 + m)%nat with (S (1 + m)) by lia. rewrite firstn_snoc by lia.
        rewrite removelast_app1. apply H4. lia.
      + intros k Hk. destruct (Nat.eq_dec k (2 + m)) as [-> | Hne].
        * unfold add_new. destruct (memb (firstn (2 + m) w) R) eqn:E; [apply memb_In, E |].
          apply in_or_app. right. left. reflexivity.
        * apply Hmem, H4. lia. }
  destruct (Hgen (length w - 1)%nat ltac:(lia)) as [H1 [H2 [H3 _]]]. auto.
Qed.

Lemma fold_prefixes_all : forall ws acc, NoDup acc -> parents_first acc ->
  NoDup (fold_left add_new (flat_map prefixes ws) acc) /\ parents_first (fold_left add_new (flat_map prefixes ws) acc).
Proof.
  induction ws as [| w ws IH]; intros acc Hnd Hpf; simpl; [auto |].
  rewrite fold_left_app. destruct (fold_prefixes w acc Hnd Hpf) as [H1 [H2 _]]. apply IH; assumption.
Qed.

Lemma mass_trie_ok : forall C, NoDup (mass_trie C) /\ parents_first (mass_trie C).
Proof.
  intros C. unfold mass_trie. apply fold_prefixes_all; [constructor |]. intros i Hi. simpl in Hi. lia.
Qed.

Lemma mass_trie_len : forall C x, In x (mass_trie C) -> (2 <= length x)%nat.
Proof.
  intros C x H. unfold mass_trie in H. apply add_new_In in H as [[] | H].
  apply in_flat_map in H as [w [_ Hw]]. apply in_prefixes in Hw as [k [Hk ->]].
  rewrite firstn_length. lia.
Qed.

(** ** The kernel's table of σ and states. *)
Section Table.
  Variable I : instance.
  Variable C : canon.
  Variable m : list (list (option Q)).
  Variable steps : list steprec.
  Notation mt := (mass_trie C).

  Definition entry_ok (acc : list tentry) (pq : list nat) (q : nat) (e : tentry) : Prop :=
    let p := removelast pq in
    let r := parent_state C acc p in
    let wt0 := wt I (last p O) (last pq O) in
    (q < length steps)%nat /\
    step_ok I C m (nth q steps (mkStep NBad None)) r (last pq O) wt0 = inr (fst e) /\
    snd e = map (fun i => nth i r 0 - wt0 * nth i (fst e) 0) (seq 0 (N I)).

  Lemma run_steps_spec : forall todo q acc tab, run_steps I C m steps todo q acc = (None, tab) ->
    exists ents, tab = acc ++ ents /\ length ents = length todo /\
      forall i, (i < length todo)%nat ->
        entry_ok (acc ++ firstn i ents) (nth i todo []) (q + i) (nth i ents ([], [])).
  Proof.
    induction todo as [| pq todo IH]; intros q acc tab H; simpl in H.
    - inversion H; subst. exists []. split; [rewrite app_nil_r; reflexivity | split; [reflexivity |]].
      intros i Hi. simpl in Hi. lia.
    - revert H. destruct (Nat.leb (length steps) q) eqn:Hq; intros H; [inversion H |].
      revert H.
      destruct (step_ok I C m (nth q steps (mkStep NBad None)) (parent_state C acc (removelast pq))
                  (last pq O) (wt I (last (removelast pq) O) (last pq O))) as [v | sg] eqn:Hs; intros H.
      { inversion H. }
      set (e := (sg, map (fun i => nth i (parent_state C acc (removelast pq)) 0 -
                                   wt I (last (removelast pq) O) (last pq O) * nth i sg 0) (seq 0 (N I)))).
      destruct (IH (S q) (acc ++ [e]) tab H) as [ents [Htab [Hlen Hok]]].
      exists (e :: ents). split; [rewrite Htab, <- app_assoc; reflexivity |].
      split; [simpl; rewrite Hlen; reflexivity |].
      intros [| i] Hi.
      + simpl. rewrite app_nil_r, Nat.add_0_r. unfold entry_ok. apply Nat.leb_gt in Hq.
        split; [exact Hq | split; [exact Hs | reflexivity]].
      + simpl in Hi |- *. specialize (Hok i ltac:(lia)). rewrite <- app_assoc in Hok.
        replace (q + S i)%nat with (S q + i)%nat by lia. exact Hok.
  Qed.
End Table.

(** ** What the guarantee branch's [Pass] says. *)
Ltac no_pass H :=
  repeat match type of H with
  | context [if ?c then _ else _] => destruct c
  | context [match ?c with _ => _ end] => destruct c
  end; try discriminate.

Lemma dp_not_pass : forall I W C m i, dp_ok I W C m i <> Some Pass.
Proof. intros I W C m i H. unfold dp_ok in H. cbv zeta in H. no_pass H. Qed.

Lemma first_v_not_pass : forall f l, (forall x, f x <> Some Pass) -> first_v f l <> Some Pass.
Proof.
  intros f. induction l as [| x l IH]; intros Hf H; cbn [first_v] in H; [discriminate |].
  destruct (f x) eqn:E; [inversion H; subst; exact (Hf x E) | exact (IH Hf H)].
Qed.

Lemma arc_not_pass : forall I C m mus, arc_ok I C m mus <> Some Pass.
Proof. intros I C m mus H. unfold arc_ok in H. cbv zeta in H. no_pass H. Qed.

Lemma stages_not_pass : forall I A o sg beta k ds, stages I A o sg beta k ds <> Some Pass.
Proof.
  intros I A o sg beta k ds. revert k. induction ds as [| d ds IH]; intros k H; cbn [stages] in H; [discriminate |].
  destruct (nums_k (dy d) (length A)), (nums_k (dfix d) k), (dz d); try discriminate.
  destruct (stage_holds I A o sg beta k _ _ _); [exact (IH _ H) | discriminate].
Qed.

Lemma step_not_pass : forall I C m rec r u wt0, step_ok I C m rec r u wt0 <> inl Pass.
Proof.
  intros I C m rec r u wt0 H. unfold step_ok in H. cbv zeta in H.
  destruct (nums_k (ssigma rec) (N I)); [| discriminate].
  destruct (sduals rec); [| discriminate].
  destruct (negb _); [discriminate |].
  destruct (all_some _); [| discriminate].
  match type of H with (if ?c then _ else _) = _ => destruct c; [discriminate |] end.
  destruct (stages _ _ _ _ _ _ _) eqn:E; [| discriminate].
  inversion H; subst. exact (stages_not_pass _ _ _ _ _ _ _ E).
Qed.

Lemma run_steps_not_pass : forall I C m steps todo q acc acc', run_steps I C m steps todo q acc <> (Some Pass, acc').
Proof.
  intros I C m steps. induction todo as [| pq todo IH]; intros q acc acc' H; cbn [run_steps] in H;
    [discriminate |].
  destruct (Nat.leb (length steps) q); [discriminate |].
  destruct (step_ok _ _ _ _ _ _ _) eqn:E.
  - inversion H; subst. exact (step_not_pass _ _ _ _ _ _ _ E).
  - exact (IH _ _ _ H).
Qed.

Lemma gtable_not_pass : forall I C gw m tab, gtable I C gw m <> (Some Pass, tab).
Proof.
  intros I C gw m tab H. unfold gtable in H. destruct (gsteps gw) as [steps |]; [| discriminate].
  destruct (run_steps I C m steps (mass_trie C) O []) as [[v |] acc] eqn:E.
  - inversion H; subst. exact (run_steps_not_pass _ _ _ _ _ _ _ _ E).
  - destruct (Nat.eqb _ _); discriminate.
Qed.

Lemma decide_guarantee_spec : forall I W C gw, decide_guarantee I W C gw = Pass ->
  exists m mus tab,
    length (gm gw) = length (normals I C) /\ all_some (map (glabels I W) (gm gw)) = Some m /\
    first_v (dp_ok I W C m) (seq 0 (length (normals I C))) = None /\
    forallb (fun i => le_ext (Some (dotq (nth i (normals I C) []) (gh C))) (get (nth i m []) (start I)))
            (seq 0 (length (normals I C))) = true /\
    covers_ok I C (gcovers gw) = Some mus /\ arc_ok I C m mus = None /\
    gtable I C gw m = (None, tab) /\ forallb (ggreedy_at I C tab) (mass_trie C) = true /\
    forallb (fun t => Qle_bool (gU I W C tab t) (nth t (gh C) 0)) (types I) = true.
Proof.
  intros I W C gw H. unfold decide_guarantee in H. cbv zeta in H.
  destruct (Nat.eqb (length (gm gw)) (length (normals I C))) eqn:E1; [| discriminate]. simpl in H.
  destruct (all_some (map (glabels I W) (gm gw))) as [m |] eqn:E2; [| discriminate].
  destruct (first_v (dp_ok I W C m) (seq 0 (length (normals I C)))) eqn:E3.
  { subst. exfalso. exact (first_v_not_pass _ _ (dp_not_pass I W C m) E3). }
  destruct (forallb _ (seq 0 (length (normals I C)))) eqn:E4; [| discriminate]. simpl in H.
  destruct (covers_ok I C (gcovers gw)) as [mus |] eqn:E5; [| discriminate].
  destruct (arc_ok I C m mus) eqn:E6.
  { subst. exfalso. exact (arc_not_pass I C m mus E6). }
  destruct (gtable I C gw m) as [[v |] tab] eqn:E7.
  { subst. exfalso. exact (gtable_not_pass I C gw m tab E7). }
  destruct (forallb (ggreedy_at I C tab) (mass_trie C)) eqn:E8; [| discriminate]. simpl in H.
  destruct (forallb _ (types I)) eqn:E9; [| discriminate].
  exists m, mus, tab. apply Nat.eqb_eq in E1. repeat split; assumption.
Qed.

Lemma removelast_len : forall (l : list nat), l <> [] -> length (removelast l) = (length l - 1)%nat.
Proof.
  intros l Hl. destruct (exists_last Hl) as [l' [x ->]]. rewrite removelast_app1, app_length. simpl. lia.
Qed.

Lemma nth_firstn_lt : forall (A : Type) (l : list A) n i d, (i < n)%nat -> nth i (firstn n l) d = nth i l d.
Proof.
  intros A. induction l as [| x l IH]; intros [| n] [| i] d H; simpl; try reflexivity; try lia.
  apply IH. lia.
Qed.

(** ** The link: the kernel's table is the rule's certified σ. *)
Section Link.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Hypothesis Hinst : instance_ok I = true.
  Hypothesis Hmixlen : length (mix C) = N I.
  Hypothesis Hmix : forall mm, In mm (mix C) -> mixture_ok I mm = true.
  Variables (h : list Q) (ex : list (list nat)).
  Hypothesis Hcr : crule C = RGuarantee h ex.
  Hypothesis Hrule : rule_ok I (crule C).
  Variable m : list (list (option Q)).
  Variable stps : list steprec.
  Variable tab : list tentry.
  Hypothesis Hrun : run_steps I C m stps (mass_trie C) O [] = (None, tab).
  Notation mt := (mass_trie C).
  Notation A := (normals I C).

  Lemma gh_h : gh C = h.
  Proof. unfold gh. rewrite Hcr. reflexivity. Qed.

  Lemma h_len : length h = N I.
  Proof. pose proof Hrule as H. unfold rule_ok in H. rewrite Hcr in H. apply H. Qed.

  Lemma A_len : forall a, In a A -> length a = N I.
  Proof.
    intros a Ha. unfold normals in Ha. apply in_app_or in Ha as [Ha | Ha].
    - apply in_map_iff in Ha as [b [<- _]]. rewrite map_length, seq_length. reflexivity.
    - apply in_map_iff in Ha as [b [<- Hb]]. rewrite map_length.
      pose proof Hrule as H. unfold rule_ok in H. rewrite Hcr in H. apply H.
      unfold gextras in Hb. rewrite Hcr in Hb. exact Hb.
  Qed.

  Lemma tab_spec : length tab = length mt /\
    forall i, (i < length mt)%nat -> entry_ok I C m stps (firstn i tab) (nth i mt []) i (nth i tab ([], [])).
  Proof.
    destruct (run_steps_spec I C m stps mt O [] tab Hrun) as [ents [-> [Hlen Hok]]].
    simpl. split; [exact Hlen |]. intros i Hi. exact (Hok i Hi).
  Qed.

  (** Every prefix of the mass trie starts at s0; the first index is the unique one. *)
  Lemma mt_start : forall x, In x mt -> exists l, x = start I :: l.
  Proof.
    intros x Hx. unfold mass_trie in Hx. apply add_new_In in Hx as [[] | Hx].
    apply in_flat_map in Hx as [w [Hw Hx]]. apply in_prefixes in Hx as [k [Hk ->]].
    unfold all_walks in Hw. apply in_flat_map in Hw as [mm [Hmm Hw]]. apply in_map_iff in Hw as [e [<- He]].
    pose proof (Hmix mm Hmm) as Hm. unfold mixture_ok in Hm. repeat rewrite andb_true_iff in Hm.
    destruct Hm as [[[_ Hall] _] _]. rewrite forallb_forall in Hall. specialize (Hall e He).
    apply andb_true_iff in Hall as [_ Hw]. destruct (walk_ok_true I _ Hw) as [l [Hl _]].
    rewrite Hl. destruct k as [| k]; [lia |]. exists (firstn k l). reflexivity.
  Qed.

  Lemma index_unique : forall x j, (j < length mt)%nat -> nth j mt [] = x -> index_of x mt = Some j.
  Proof.
    intros x j Hj Heq. destruct (index_of_In x mt) as [j' Hj'].
    { rewrite <- Heq. apply nth_In. exact Hj. }
    destruct (index_of_nth x mt j' Hj') as [Hn Hl]. rewrite Hj'. f_equal.
    destruct (mass_trie_ok C) as [Hnd _].
    apply (proj1 (NoDup_nth mt []) Hnd j' j Hl Hj). rewrite Hn, Heq. reflexivity.
  Qed.

  Lemma parent_firstn : forall i, (i < length mt)%nat ->
    parent_state C (firstn i tab) (removelast (nth i mt [])) = parent_state C tab (removelast (nth i mt [])).
  Proof.
    intros i Hi. unfold parent_state.
    destruct (index_of (removelast (nth i mt [])) mt) as [j |] eqn:Ej; [| reflexivity].
    destruct (index_of_nth _ _ _ Ej) as [Hn Hjl].
    assert (Hlen : (3 <= length (nth i mt []))%nat).
    { pose proof (mass_trie_len C (nth j mt []) (nth_In _ [] Hjl)) as H2. rewrite Hn in H2.
      destruct (nth i mt []) as [| x l] eqn:Ex; [simpl in H2; lia |].
      rewrite removelast_len in H2 by discriminate. lia. }
    destruct (mass_trie_ok C) as [_ Hpf]. destruct (Hpf i Hi Hlen) as [j' [Hj' Heq]].
    rewrite (index_unique _ j' ltac:(lia) Heq) in Ej. inversion Ej; subst j'.
    rewrite nth_firstn_lt by exact Hj'. reflexivity.
  Qed.

  Definition kst (pr : list nat) : list Q := parent_state C tab pr.

  Definition cert (q : list nat) (i : nat) : Q :=
    match index_of (rev q) mt with Some k => nth i (fst (nth k tab ([], []))) 0 | None => 0 end.

  Notation rcG := (rc nat (wt I) (fun i => nth i h 0) cert).

  Lemma kst_root : kst [start I] = h.
  Proof.
    unfold kst, parent_state. destruct (index_of [start I] mt) as [j |] eqn:E; [| apply gh_h].
    destruct (index_of_nth _ _ _ E) as [Hn Hj]. pose proof (mass_trie_len C _ (nth_In _ [] Hj)) as H2.
    rewrite Hn in H2. simpl in H2. lia.
  Qed.

  Lemma entry_at : forall k, (k < length mt)%nat ->
    let pq := nth k mt [] in
    let r := kst (removelast pq) in
    let wt0 := wt I (last (removelast pq) O) (last pq O) in
    (k < length stps)%nat /\
    step_ok I C m (nth k stps (mkStep NBad None)) r (last pq O) wt0 = inr (fst (nth k tab ([], []))) /\
    snd (nth k tab ([], [])) = map (fun i => nth i r 0 - wt0 * nth i (fst (nth k tab ([], []))) 0) (seq 0 (N I)).
  Proof.
    intros k Hk. destruct tab_spec as [_ Hok]. specialize (Hok k Hk). unfold entry_ok in Hok.
    rewrite (parent_firstn k Hk) in Hok. exact Hok.
  Qed.

  Lemma tab_nth : forall k d1 d2, (k < length mt)%nat -> nth k tab d1 = nth k tab d2.
  Proof. intros k d1 d2 Hk. apply nth_indep. rewrite (proj1 tab_spec). exact Hk. Qed.

  Lemma kst_len : forall pr, length (kst pr) = N I.
  Proof.
    intros pr. unfold kst, parent_state. destruct (index_of pr mt) as [k |] eqn:E.
    - destruct (index_of_nth _ _ _ E) as [_ Hk]. destruct (entry_at k Hk) as [_ [_ Hs]].
      rewrite (tab_nth k _ ([], [])) by exact Hk.
      rewrite Hs, map_length, seq_length. reflexivity.
    - rewrite gh_h. apply h_len.
  Qed.

  (** The rule's state along the certified σ is the kernel's. *)
  Lemma rc_kst : forall hh u, (hh = [] /\ u = start I) \/ In (rev (u :: hh)) mt ->
    forall i, (i < N I)%nat -> rcG hh u i == nth i (kst (rev (u :: hh))) 0.
  Proof.
    induction hh as [| x hh IH]; intros u Hin i Hi.
    - destruct Hin as [[_ ->] | Hin].
      + simpl. rewrite kst_root. reflexivity.
      + pose proof (mass_trie_len C _ Hin). simpl in H. lia.
    - destruct Hin as [[Hc _] | Hin]; [discriminate |].
      destruct (In_nth _ _ [] Hin) as [k [Hk Hnth]].
      pose proof (index_unique _ k Hk Hnth) as Hidx.
      destruct (entry_at k Hk) as [_ [_ Hs]]. rewrite Hnth in Hs.
      change (rev (u :: x :: hh)) with (rev (x :: hh) ++ [u]) in Hs.
      rewrite removelast_app1, last_app1, last_rev_cons in Hs.
      assert (Hk2 : kst (rev (u :: x :: hh)) = snd (nth k tab ([], []))).
      { unfold kst, parent_state. rewrite Hidx. rewrite (tab_nth k _ ([], [])) by exact Hk. reflexivity. }
      rewrite Hk2, Hs. rewrite (nth_map_lt _ _ _ (seq 0 (N I)) i O 0) by (rewrite seq_length; exact Hi).
      rewrite seq_nth by exact Hi. simpl rcG. cbn [rc].
      unfold cert. rewrite Hidx. rewrite <- IH; [reflexivity | | exact Hi].
      (* the parent is the start or in the trie *)
      destruct hh as [| y hh'].
      + left. split; [reflexivity |]. destruct (mt_start _ Hin) as [l Hl].
        simpl in Hl. destruct l as [| a [| b l]]; simpl in Hl; inversion Hl; reflexivity.
      + right. destruct (mass_trie_ok C) as [_ Hpf].
        assert (H3 : (3 <= length (nth k mt []))%nat) by (rewrite Hnth; simpl; rewrite !app_length; simpl; lia).
        destruct (Hpf k Hk H3) as [j [Hj Heq]]. rewrite Hnth in Heq.
        change (rev (u :: x :: y :: hh')) with (rev (x :: y :: hh') ++ [u]) in Heq.
        rewrite removelast_app1 in Heq. rewrite <- Heq. apply nth_In. lia.
  Qed.

  Lemma step_in_mt : forall t p l0 q, (t < N I)%nat -> In (p, l0) (gamma C t) ->
    In q (steps nat [] (start I) l0) -> In (rev q) mt /\ exists e, In e (nth t (mix C) []) /\ fst e = start I :: l0.
  Proof.
    intros t p l0 q Ht Hpl Hq. unfold gamma in Hpl. apply in_map_iff in Hpl as [e [He Hin]].
    inversion He; subst p l0.
    destruct (mix_walk0 I C Hmixlen Hmix t e Ht Hin) as [_ [l [Hl _]]]. rewrite Hl in Hq. simpl tl in Hq.
    split; [| exists e; split; [exact Hin | rewrite Hl; reflexivity]].
    destruct (proj1 (steps_firstn l [] (start I) q) Hq) as [k [Hk Hqk]].
    assert (Hq2 : (2 <= length q)%nat) by (rewrite Hqk, app_length, rev_length, firstn_length; simpl; lia).
    pose proof (proj1 (step_prefix (start I) l q Hq2) Hq) as Hpre.
    unfold mass_trie. apply add_new_In. right. apply in_flat_map. exists (fst e). split.
    - unfold all_walks. apply in_flat_map. exists (nth t (mix C) []). split; [apply nth_In; lia | apply in_map; exact Hin].
    - apply in_prefixes. unfold is_prefix in Hpre. apply leqb_eq in Hpre. rewrite Hl.
      exists (length (rev q)). split.
      + rewrite rev_length. split; [exact Hq2 |].
        apply (f_equal (@length nat)) in Hqk. rewrite !app_length, rev_length, firstn_length in Hqk. simpl in *. lia.
      + exact Hpre.
  Qed.

  Definition live (v : nat) : Prop := exists mu, all_some (map (fun i => get (nth i m []) v) (seq 0 (length A))) = Some mu.

  Definition mq (v : nat) : list Q := map (fun i => match get (nth i m []) v with Some x => x | None => 0 end) (seq 0 (length A)).

  Lemma mq_mu : forall v mu, all_some (map (fun i => get (nth i m []) v) (seq 0 (length A))) = Some mu ->
    forall k, nth k (mq v) 0 == nth k mu 0.
  Proof.
    intros v mu H k. unfold mq. destruct (Nat.lt_ge_cases k (length A)) as [Hk | Hk].
    - rewrite (nth_map_lt _ _ _ (seq 0 (length A)) k O 0) by (rewrite seq_length; exact Hk).
      rewrite seq_nth by exact Hk. simpl.
      pose proof (all_some_nth _ _ _ k 0 H ltac:(rewrite map_length, seq_length; exact Hk)) as Hn.
      rewrite (nth_map_lt _ _ _ (seq 0 (length A)) k O None) in Hn by (rewrite seq_length; exact Hk).
      rewrite seq_nth in Hn by exact Hk. simpl in Hn. rewrite Hn. reflexivity.
    - rewrite !nth_overflow; [reflexivity | | ].
      + rewrite (all_some_len _ _ _ H), map_length, seq_length. exact Hk.
      + rewrite map_length, seq_length. exact Hk.
  Qed.

  (** At every step of a profile walk the certified σ is the rule's lexicographic minimum. *)
  Theorem cert_ok : forall t p l0 q v u hh, In t (seq 0 (N I)) -> In (p, l0) (gamma C t) ->
    In q (steps nat [] (start I) l0) -> q = v :: u :: hh ->
    live v /\ lexmin (N I) A (betaF (N I) nat A mq (rcG hh u) v (wt I u v)) (order I) (cert q).
  Proof.
    intros t p l0 q v u hh Ht Hpl Hq Hqe. apply in_seq in Ht.
    destruct (step_in_mt t p l0 q ltac:(lia) Hpl Hq) as [Hmt _].
    destruct (In_nth _ _ [] Hmt) as [k [Hk Hnth]].
    pose proof (index_unique _ k Hk Hnth) as Hidx.
    destruct (entry_at k Hk) as [_ [Hstep _]]. rewrite Hnth in Hstep. subst q.
    change (rev (v :: u :: hh)) with (rev (u :: hh) ++ [v]) in Hstep.
    rewrite removelast_app1, last_app1, last_rev_cons in Hstep.
    destruct (step_ok_lexmin I C A_len m _ _ _ _ _ (kst_len _) Hstep) as [mu [Hmu [Hsl Hlex]]].
    split; [exists mu; exact Hmu |].
    apply (lexmin_ext _ _ (fun k0 => (dotq (nth k0 A []) (kst (rev (u :: hh))) - nth k0 mu 0) / wt I u v)).
    - intros k0. unfold betaF. rewrite (mq_mu v mu Hmu k0).
      destruct (Nat.lt_ge_cases k0 (length A)) as [Hk0 | Hk0].
      + rewrite (dotq_dotv (N I)); [| apply A_len, nth_In, Hk0 | apply kst_len].
        unfold dotv. rewrite (sumL_ext (fun i => nth i (nth k0 A []) 0 * nth i (kst (rev (u :: hh))) 0)
                                       (fun i => nth i (nth k0 A []) 0 * rcG hh u i)); [reflexivity |].
        intros i Hi. apply in_seq in Hi. rewrite rc_kst; [reflexivity | | lia].
        destruct hh as [| x hh'].
        * destruct (mt_start _ Hmt) as [l Hl]. simpl in Hl. inversion Hl. left. auto.
        * right. destruct (mass_trie_ok C) as [_ Hpf].
          assert (H3 : (3 <= length (nth k mt []))%nat) by (rewrite Hnth; simpl; rewrite !app_length; simpl; lia).
          destruct (Hpf k Hk H3) as [j [Hj Heq]]. rewrite Hnth in Heq.
          change (rev (v :: u :: x :: hh')) with (rev (u :: x :: hh') ++ [v]) in Heq.
          rewrite removelast_app1 in Heq. rewrite <- Heq. apply nth_In. lia.
      + rewrite (nth_overflow A) by exact Hk0. unfold dotv. change (dotq [] (kst (rev (u :: hh)))) with 0.
        rewrite sumL_zero; [reflexivity | intros i _; destruct i; simpl; ring].
    - unfold cert. rewrite Hidx. exact Hlex.
  Qed.

  Lemma gamma_live : forall t p l0, In t (seq 0 (N I)) -> In (p, l0) (gamma C t) -> forall x, In x l0 -> live x.
  Proof.
    intros t p l0 Ht Hpl x Hx. destruct (In_nth _ _ O Hx) as [j [Hj Hxj]].
    set (q := rev (firstn (S j) l0) ++ [start I]).
    assert (Hq : In q (steps nat [] (start I) l0)) by (apply steps_firstn; exists (S j); split; [lia | reflexivity]).
    assert (Hshape : exists u hh, q = x :: u :: hh).
    { unfold q. rewrite (firstn_snoc l0 j Hj), rev_app_distr. simpl. rewrite Hxj.
      destruct (rev (firstn j l0) ++ [start I]) as [| u hh] eqn:E; [destruct (rev (firstn j l0)); discriminate |].
      exists u, hh. reflexivity. }
    destruct Hshape as [u [hh Hqs]].
    exact (proj1 (cert_ok t p l0 q x u hh Ht Hpl Hq Hqs)).
  Qed.

  Lemma Jc_gwcost : forall t l hh u,
    Jc nat (wt I) (Dv W) cert t hh u l == gwcost I W C tab t (rev (u :: hh)) l.
  Proof.
    intros t. induction l as [| v l IH]; intros hh u.
    - cbn [Jc gwcost]. rewrite last_rev_cons. reflexivity.
    - cbn [Jc gwcost]. change (rev (u :: hh) ++ [v]) with (rev (v :: u :: hh)).
      rewrite IH, last_rev_cons. unfold gsig_t, cert.
      change (rev (u :: hh) ++ [v]) with (rev (v :: u :: hh)). reflexivity.
  Qed.

  Lemma Ucert_gU : forall t, (t < N I)%nat ->
    Ucert nat (wt I) (Dv W) (start I) (gamma C) cert t == gU I W C tab t.
  Proof.
    intros t Ht. unfold Ucert, gU, gamma. rewrite qsum_sumL, sumL_map. apply sumL_ext. intros e He. simpl.
    destruct (mix_walk0 I C Hmixlen Hmix t e Ht He) as [_ [l [Hl _]]]. rewrite Hl. simpl.
    rewrite (Jc_gwcost t l [] (start I)). reflexivity.
  Qed.

  Hypothesis Hgr : forallb (ggreedy_at I C tab) mt = true.

  Theorem greedy_cert : forall q v u hh,
    on_path nat (seq 0 (N I)) nat Nat.eq_dec (start I) (priorq I) (gamma C) q -> q = v :: u :: hh ->
    forall t t', In t (seq 0 (N I)) -> In t' (seq 0 (N I)) -> 0 < cert q t ->
      Game.mass nat nat Nat.eq_dec (start I) (priorq I) (gamma C) t' q <=
      Game.mass nat nat Nat.eq_dec (start I) (priorq I) (gamma C) t q.
  Proof.
    intros q v u hh Hon Hqe t t' Ht Ht' Hpos.
    destruct (on_path_step nat (seq 0 (N I)) nat Nat.eq_dec (start I) (priorq I) (prior_nonneg I Hinst)
                (gamma C) q Hon) as [t0 [p0 [l0 [Ht0 [Hpl0 Hq0]]]]].
    apply in_seq in Ht0. destruct (step_in_mt t0 p0 l0 q ltac:(lia) Hpl0 Hq0) as [Hmt _].
    subst q. unfold mt in Hgr. rewrite forallb_forall in Hgr. specialize (Hgr _ Hmt).
    unfold ggreedy_at in Hgr. rewrite forallb_forall in Hgr.
    change (rev (v :: u :: hh)) with (rev (u :: hh) ++ [v]) in Hgr.
    rewrite removelast_app1, last_app1 in Hgr.
    rewrite !(mass_eq I C Hmixlen Hmix) by (simpl; lia).
    change (rev (v :: u :: hh)) with (rev (u :: hh) ++ [v]).
    specialize (Hgr t Ht). apply negb_true_iff in Hgr.
    assert (Hc : gsig_t C tab (rev (u :: hh)) v t == cert (v :: u :: hh) t) by (unfold gsig_t, cert; reflexivity).
    unfold types in Hgr.
    assert (Htop : 0 < qmax (map (fun t => Kernel.mass I C t (rev (u :: hh) ++ [v])) (seq 0 (N I)))).
    { unfold on_path, Game.Z in Hon. destruct (sum_pos nat _ _ Hon) as [t1 [Ht1 Hm1]].
      rewrite (mass_eq I C Hmixlen Hmix) in Hm1 by (simpl; lia).
      change (rev (v :: u :: hh)) with (rev (u :: hh) ++ [v]) in Hm1.
      pose proof (qmax_ge _ _ (in_map (fun t => Kernel.mass I C t (rev (u :: hh) ++ [v])) _ _ Ht1)). lra. }
    apply ltb_lt in Htop. assert (Hp2 : ltb 0 (gsig_t C tab (rev (u :: hh)) v t) = true) by (apply ltb_lt; lra).
    rewrite Htop, Hp2, !andb_true_l in Hgr. apply ltb_false in Hgr.
    pose proof (qmax_ge _ _ (in_map (fun t => Kernel.mass I C t (rev (u :: hh) ++ [v])) _ _ Ht')). lra.
  Qed.
End Link.

(** ** NR.2 in the kernel's terms, and what the kernel's checks give it. *)
Section NR2.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Variable m : list (list (option Q)).
  Notation A := (normals I C).

  (** The premises NR.2 needs, as the kernel checks them: the labels satisfy the
      rule's DP equations (NR.1(c)); h ∈ F_{s0}; and on every arc (v, u) of the
      game with finite labels, every r ∈ F_v satisfies λ·(A r) ≤ w + λ·m(u) in
      every direction λ of [arc_dirs] (the packing polytope's vertices the DP's
      equations do not imply). *)
  Definition nr2_premises : Prop :=
    (forall i, (i < length A)%nat -> dp_ok I W C m i = None) /\
    (forall i x, (i < length A)%nat -> get (nth i m []) (start I) = Some x ->
                 dotv (N I) (nth i A []) (fun j => nth j (gh C) 0) <= x) /\
    (forall ds lam, arc_dirs I C = Some ds -> In lam ds ->
       forall v u, has_arc I v u = true -> isgoal I v = false -> live I C m v -> live I C m u ->
       forall r, (forall i, (i < length A)%nat -> dotv (N I) (nth i A []) r <= nth i (mq I C m v) 0) ->
       sumL (fun a => nth a lam 0 * dotv (N I) (nth a A []) r) (seq 0 (length A)) <=
       wt I v u + sumL (fun a => nth a lam 0 * nth a (mq I C m u) 0) (seq 0 (length A))).

  (** NR.2 (proofs/NRULE.md, the one step that stays a written proof): under
      those premises every walk of the game costs type t at least h_t against
      a Defender that follows the rule.  It includes the Farkas part of NR.2
      (the directions of [arc_dirs] describe F_u + wΔ, NG.8(c)) and why the
      implied directions may be skipped (K.7). *)
  Definition NR2 (s : wstrat nat nat) : Prop :=
    nr2_premises -> forall t, In t (types I) -> forall l, gwalk nat (fun a b => has_arc I a b = true) (isgoal I) (start I) l ->
      nth t (gh C) 0 <= J nat nat (wt I) (Dv W) t s [] (start I) l.

  (** *** The kernel's checks establish the premises. *)
  Lemma first_v_none : forall f l, first_v f l = None -> forall x, In x l -> f x = None.
  Proof.
    intros f. induction l as [| y l IH]; intros H x Hx; [destruct Hx |]. cbn [first_v] in H.
    destruct (f y) eqn:E; [discriminate |]. destruct Hx as [<- | Hx]; [exact E | exact (IH H x Hx)].
  Qed.

  Hypothesis Hinst2 : instance_ok I = true.

  Lemma live_get : forall v mu, all_some (map (fun i => get (nth i m []) v) (seq 0 (length A))) = Some mu ->
    forall j, (j < length A)%nat -> get (nth j m []) v = Some (nth j (mq I C m v) 0).
  Proof.
    intros v mu H j Hj. pose proof (all_some_nth _ _ _ j 0 H ltac:(rewrite map_length, seq_length; exact Hj)) as Hn.
    rewrite (nth_map_lt _ _ _ (seq 0 (length A)) j O None) in Hn by (rewrite seq_length; exact Hj).
    rewrite seq_nth in Hn by exact Hj. simpl in Hn. rewrite Hn. unfold mq.
    rewrite (nth_map_lt _ _ _ (seq 0 (length A)) j O 0) by (rewrite seq_length; exact Hj).
    rewrite seq_nth by exact Hj. simpl. rewrite Hn. reflexivity.
  Qed.

  Lemma combine_at_live : forall v, live I C m v -> forall c, (length c <= length A)%nat ->
    exists b, combine_at c m v = Some b /\
              b == sumL (fun a => nth a c 0 * nth a (mq I C m v) 0) (seq 0 (length c)).
  Proof.
    intros v [mu Hmu] c Hc. unfold combine_at.
    assert (Hgen : forall c k, (k + length c <= length A)%nat ->
      exists b, fold_right (fun jc acc => if Qeq_bool (fst jc) 0 then acc else
                              match acc, get (nth (snd jc) m []) v with
                              | Some x, Some y => Some (x + fst jc * y)
                              | _, _ => None end) (Some 0) (combine c (seq k (length c))) = Some b /\
                b == sumL (fun a => nth a c 0 * nth (k + a) (mq I C m v) 0) (seq 0 (length c))).
    { induction c0 as [| x c0 IH]; intros k Hk.
      - exists 0. split; reflexivity.
      - destruct (IH (S k) ltac:(simpl in Hk; lia)) as [b [Hb Hbe]].
        change (combine (x :: c0) (seq k (length (x :: c0)))) with ((x, k) :: combine c0 (seq (S k) (length c0))).
        cbn [fold_right fst snd]. rewrite Hb.
        assert (Hsum : sumL (fun a => nth a (x :: c0) 0 * nth (k + a) (mq I C m v) 0) (seq 0 (length (x :: c0))) ==
                       x * nth k (mq I C m v) 0 +
                       sumL (fun a => nth a c0 0 * nth (S k + a) (mq I C m v) 0) (seq 0 (length c0))).
        { change (length (x :: c0)) with (S (length c0)). cbn [seq sumL].
          rewrite <- (seq_shift (length c0) 0), sumL_map, Nat.add_0_r.
          apply Qplus_comp; [reflexivity |]. apply sumL_ext. intros a _. cbn [nth].
          replace (k + S a)%nat with (S k + a)%nat by lia. reflexivity. }
        destruct (Qeq_bool x 0) eqn:Ex.
        + exists b. split; [reflexivity |]. rewrite Hsum. apply Qeq_bool_iff in Ex. rewrite Ex, Hbe. ring.
        + rewrite (live_get v mu Hmu k ltac:(simpl in Hk; lia)). eexists. split; [reflexivity |].
          rewrite Hsum, Hbe. ring. }
    destruct (Hgen c O ltac:(lia)) as [b [Hb Hbe]]. exists b. split; [exact Hb | exact Hbe].
  Qed.

  Lemma orelax_le : forall f k v u w, In (u, w) (arcs I v) -> ole (orelax I f k v) (oaddq (k * w) (f u)).
  Proof.
    intros f k v u w Hin. unfold orelax. induction (arcs I v) as [| a l IH]; [destruct Hin |]. simpl.
    destruct Hin as [-> | Hin].
    - simpl. rewrite oadd_oaddq. apply omin_le_left.
    - eapply ole_trans; [apply omin_le_right | exact (IH Hin)].
  Qed.

  Lemma fold_omin_some : forall (g : list Q -> option Q) l b,
    fold_right (fun mu acc => omin (g mu) acc) None l = Some b -> exists mu, In mu l /\ g mu = Some b.
  Proof.
    intros g. induction l as [| x l IH]; intros b H; simpl in H; [discriminate |].
    destruct (g x) as [y |] eqn:Eg; destruct (fold_right _ None l) as [z |] eqn:Ef; simpl in H.
    - destruct (Qle_bool y z); inversion H; subst.
      + exists x. split; [left; reflexivity | exact Eg].
      + destruct (IH b eq_refl) as [mu [Hmu Hg]]. exists mu. split; [right; exact Hmu | exact Hg].
    - inversion H; subst. exists x. split; [left; reflexivity | exact Eg].
    - destruct (IH b H) as [mu [Hmu Hg]]. exists mu. split; [right; exact Hmu | exact Hg].
    - discriminate.
  Qed.

  Lemma fold_omin_le : forall (g : list Q -> option Q) l mu, In mu l ->
    ole (fold_right (fun mu acc => omin (g mu) acc) None l) (g mu).
  Proof.
    intros g. induction l as [| x l IH]; intros mu Hin; [destruct Hin |]. simpl.
    destruct Hin as [-> | Hin]; [apply omin_le_left |].
    eapply ole_trans; [apply omin_le_right | exact (IH mu Hin)].
  Qed.

  Lemma exchange : forall (lam : list Q) (r : nat -> Q),
    sumL (fun a => nth a lam 0 * dotv (N I) (nth a A []) r) (seq 0 (length A)) ==
    sumL (fun i => sumL (fun a => nth a lam 0 * nth i (nth a A []) 0) (seq 0 (length A)) * r i) (seq 0 (N I)).
  Proof.
    intros lam r. unfold dotv.
    rewrite (sumL_ext (fun a => nth a lam 0 * sumL (fun i => nth i (nth a A []) 0 * r i) (seq 0 (N I)))
                      (fun a => sumL (fun i => nth a lam 0 * nth i (nth a A []) 0 * r i) (seq 0 (N I)))).
    - rewrite sumL_swap. apply sumL_ext. intros i _. rewrite sumL_scale_r. reflexivity.
    - intros a _. rewrite <- sumL_scale. apply sumL_ext. intros i _. ring.
  Qed.


  Lemma sum_pad : forall (c : list Q) (f : nat -> Q) K, (length c <= K)%nat ->
    sumL (fun a => nth a c 0 * f a) (seq 0 (length c)) == sumL (fun a => nth a c 0 * f a) (seq 0 K).
  Proof.
    intros c f K H. replace K with (length c + (K - length c))%nat by lia.
    rewrite seq_app, sumL_app. rewrite (sumL_zero _ (seq (0 + length c) _)); [ring |].
    intros a Ha. apply in_seq in Ha. rewrite nth_overflow by lia. ring.
  Qed.

  Lemma leqq_nth : forall a b, leqq a b = true -> forall i, nth i a 0 == nth i b 0.
  Proof.
    intros a b H. unfold leqq in H. apply andb_true_iff in H as [Hl H]. apply Nat.eqb_eq in Hl.
    revert b Hl H. induction a as [| x a IH]; intros [| y b] Hl H i; simpl in *; try discriminate;
      [destruct i; reflexivity |].
    apply andb_true_iff in H as [Hxy H]. destruct i as [| i]; [apply Qeq_bool_iff, Hxy |].
    apply IH; [lia | exact H].
  Qed.

  Lemma col_sum : forall (c : list Q) i, (length c <= length A)%nat ->
    dotq c (map (fun a => nth i a 0) A) == sumL (fun a => nth a c 0 * nth i (nth a A []) 0) (seq 0 (length A)).
  Proof.
    intros c i Hc. rewrite dotq_sum, map_length. replace (Nat.min (length c) (length A)) with (length c) by lia.
    rewrite (sumL_ext _ (fun a => nth a c 0 * nth i (nth a A []) 0)).
    - apply sum_pad. exact Hc.
    - intros a Ha. apply in_seq in Ha. rewrite (nth_map_lt _ _ _ A a [] 0) by lia. reflexivity.
  Qed.

  Lemma vertices_nonneg : forall cols rhs vs, vertices cols rhs = Some vs ->
    forall x, In x vs -> forall i, 0 <= nth i x 0.
  Proof.
    intros cols rhs vs H x Hx i. unfold vertices in H. cbv zeta in H.
    destruct (Z.ltb _ _); [discriminate |]. inversion H; subst vs. clear H.
    apply in_flat_map in Hx as [K [_ Hx]].
    destruct (solve (map (fun j => nth j cols []) K) rhs) as [y |]; [| destruct Hx].
    destruct (forallb (fun v => ltb 0 v) y) eqn:Hy; [| destruct Hx].
    destruct Hx as [<- | []]. rewrite forallb_forall in Hy.
    destruct (Nat.lt_ge_cases i (length cols)) as [Hi | Hi].
    - rewrite (nth_map_lt _ _ _ (seq 0 (length cols)) i O 0) by (rewrite seq_length; exact Hi).
      rewrite seq_nth by exact Hi. simpl.
      destruct (find_index i K) as [j |]; [| lra].
      destruct (Nat.lt_ge_cases j (length y)) as [Hj | Hj].
      + pose proof (Hy _ (nth_In _ 0 Hj)) as Hp. apply ltb_lt in Hp. lra.
      + rewrite nth_overflow by exact Hj. lra.
    - rewrite nth_overflow by (rewrite map_length, seq_length; exact Hi). lra.
  Qed.

  Lemma arc_dirs_spec : forall ds lam, arc_dirs I C = Some ds -> In lam ds ->
    (length lam <= length A)%nat /\ forall k, 0 <= nth k lam 0.
  Proof.
    intros ds lam H Hl. unfold arc_dirs in H. cbv zeta in H.
    destruct (vertices _ _) as [vs |] eqn:Hv; [| discriminate]. inversion H; subst ds.
    apply filter_In in Hl as [Hl _]. apply in_map_iff in Hl as [l0 [<- Hl0]].
    split; [rewrite firstn_length; lia |].
    intros k. destruct (Nat.lt_ge_cases k (length A)) as [Hk | Hk].
    - rewrite nth_firstn_lt by exact Hk. exact (vertices_nonneg _ _ _ Hv l0 Hl0 k).
    - rewrite nth_overflow by (rewrite firstn_length; lia). lra.
  Qed.

  Lemma covers_spec : forall cs mus, covers_ok I C cs = Some mus -> forall mu, In mu mus ->
    length mu = length A /\ forall k, 0 <= nth k mu 0.
  Proof.
    intros cs mus H. unfold covers_ok in H. revert mus H.
    induction cs as [| c cs IH]; intros mus H mu Hmu; simpl in H; [inversion H; subst; destruct Hmu |].
    destruct c as [| l]; [discriminate |].
    destruct (Nat.eqb (length l) (length A)) eqn:El; [| discriminate].
    destruct (all_some l) as [mu0 |] eqn:Ea; [| discriminate].
    destruct (forallb (fun x => Qle_bool 0 x) mu0) eqn:En; [| discriminate].
    destruct (all_some (map _ cs)) as [rest |] eqn:Er; simpl in H; [| discriminate].
    inversion H; subst mus. destruct Hmu as [<- | Hmu]; [| exact (IH rest eq_refl mu Hmu)].
    apply Nat.eqb_eq in El. split; [rewrite (all_some_len _ _ _ Ea); exact El |].
    intros k. rewrite forallb_forall in En. destruct (Nat.lt_ge_cases k (length mu0)) as [Hk | Hk].
    - apply Qle_bool_iff, En, nth_In, Hk.
    - rewrite nth_overflow by exact Hk. lra.
  Qed.

  Theorem prem_arc : forall cs mus, covers_ok I C cs = Some mus -> arc_ok I C m mus = None ->
    forall ds lam, arc_dirs I C = Some ds -> In lam ds ->
       forall v u, has_arc I v u = true -> isgoal I v = false -> live I C m v -> live I C m u ->
       forall r, (forall i, (i < length A)%nat -> dotv (N I) (nth i A []) r <= nth i (mq I C m v) 0) ->
       sumL (fun a => nth a lam 0 * dotv (N I) (nth a A []) r) (seq 0 (length A)) <=
       wt I v u + sumL (fun a => nth a lam 0 * nth a (mq I C m u) 0) (seq 0 (length A)).
  Proof.
    intros cs mus Hcov Harc ds lam Hds Hlam v u Huv Hg Hv Hu r Hr.
    destruct (arc_dirs_spec ds lam Hds Hlam) as [Hll Hl0].
    unfold arc_ok in Harc. rewrite Hds in Harc.
    destruct (forallb _ ds) eqn:Hall; [| discriminate]. rewrite forallb_forall in Hall.
    specialize (Hall lam Hlam). cbv beta zeta in Hall. rewrite forallb_forall in Hall.
    assert (Hvn : In v (seq 0 (n I))) by (apply in_seq; pose proof (arc_src I v u Huv); lia).
    specialize (Hall v Hvn). rewrite Hg in Hall. simpl in Hall. apply le_ext_ole in Hall.
    pose proof (orelax_le (combine_at lam m) 1 v u (wt I v u) (has_arc_wt I v u Huv)) as Hrel.
    destruct (combine_at_live u Hu lam Hll) as [bu [Hbu Hbue]]. rewrite Hbu in Hrel. simpl in Hrel.
    pose proof (ole_trans _ _ _ Hall Hrel) as Hmin.
    set (cands := filter (fun mu => leqq (ydir I C mu) (ydir I C lam)) mus ++ [lam]) in *.
    destruct (fold_right (fun mu acc => omin (combine_at mu m v) acc) None cands) as [b |] eqn:Hb;
      [| contradiction].
    simpl in Hmin. destruct (fold_omin_some _ _ _ Hb) as [mu [Hmu Hcm]].
    assert (Hmu_ok : (length mu <= length A)%nat /\ (forall k, 0 <= nth k mu 0) /\
                     forall i, (i < N I)%nat -> dotq mu (map (fun a => nth i a 0) A) ==
                                               dotq lam (map (fun a => nth i a 0) A)).
    { apply in_app_or in Hmu as [Hmu | [<- | []]].
      - apply filter_In in Hmu as [Hmu Hy]. destruct (covers_spec cs mus Hcov mu Hmu) as [Hlen Hnn].
        split; [lia | split; [exact Hnn |]]. intros i Hi. pose proof (leqq_nth _ _ Hy i) as Hyi.
        unfold ydir in Hyi. rewrite !(nth_map_lt _ _ _ (seq 0 (N I)) i O 0) in Hyi by (rewrite seq_length; exact Hi).
        rewrite seq_nth in Hyi by exact Hi. exact Hyi.
      - split; [exact Hll | split; [exact Hl0 | intros; reflexivity]]. }
    destruct Hmu_ok as [Hml [Hmn Hcol]].
    destruct (combine_at_live v Hv mu Hml) as [bv [Hbv Hbve]]. rewrite Hcm in Hbv. inversion Hbv; subst bv.
    rewrite (exchange lam r).
    rewrite (sumL_ext _ (fun i => sumL (fun a => nth a mu 0 * nth i (nth a A []) 0) (seq 0 (length A)) * r i)).
    2: { intros i Hi. apply in_seq in Hi. specialize (Hcol i ltac:(lia)).
         rewrite !col_sum in Hcol by lia. rewrite Hcol. reflexivity. }
    rewrite <- (exchange mu r).
    apply (Qle_trans _ (sumL (fun a => nth a mu 0 * nth a (mq I C m v) 0) (seq 0 (length A)))).
    - apply sumL_le. intros a Ha. apply in_seq in Ha. apply Qmul_le_l; [apply Hmn | apply Hr; lia].
    - rewrite <- (sum_pad mu (fun a => nth a (mq I C m v) 0) (length A) Hml), <- Hbve.
      rewrite <- (sum_pad lam (fun a => nth a (mq I C m u) 0) (length A) Hll), <- Hbue. lra.
  Qed.
End NR2.

Lemma prem_h : forall I C m, (forall a, In a (normals I C) -> length a = N I) -> length (gh C) = N I ->
  forallb (fun i => le_ext (Some (dotq (nth i (normals I C) []) (gh C))) (get (nth i m []) (start I)))
          (seq 0 (length (normals I C))) = true ->
  forall i x, (i < length (normals I C))%nat -> get (nth i m []) (start I) = Some x ->
    dotv (N I) (nth i (normals I C) []) (fun j => nth j (gh C) 0) <= x.
Proof.
  intros I C m HA Hh H i x Hi Hx. rewrite forallb_forall in H.
  specialize (H i (proj2 (in_seq _ _ _) (conj (Nat.le_0_l i) Hi))).
  rewrite Hx in H. simpl in H. apply Qle_bool_iff in H.
  rewrite <- dotq_dotv; [exact H | apply HA, nth_In, Hi | exact Hh].
Qed.

(** ** The soundness theorem of the guarantee branch, modulo NR.2: if the
    kernel accepts a guarantee-rule profile, every Defender that follows the
    rule (with the witness's labels) and for which NR.2 holds is, with the
    profile's Attacker and Bayes beliefs, a weak PBNE of the untruncated game. *)
Theorem kernel_sound_guarantee : forall I P W C h ex, decide I P W = Pass ->
  read_profile I P = Some C -> crule C = RGuarantee h ex ->
  (forall j v, (j < N I)%nat -> (v < n I)%nat -> is_distance (adj I) (goal I j) v (D W j v)) /\
  exists gw m, wguarantee W = Some (Some gw) /\ all_some (map (glabels I W) (gm gw)) = Some m /\
  forall s : wstrat nat nat,
    (forall hh u v, dist nat (types I) (s hh u v)) ->
    (forall hh u v, has_arc I u v = true -> live I C m v ->
       (exists x, inF (N I) (normals I C) (betaF (N I) nat (normals I C) (mq I C m)
                    (rstate nat (wt I) (fun i => nth i h 0) s hh u) v (wt I u v)) x) ->
       lexmin (N I) (normals I C) (betaF (N I) nat (normals I C) (mq I C m)
                (rstate nat (wt I) (fun i => nth i h 0) s hh u) v (wt I u v)) (order I) (s hh u v)) ->
    NR2 I W C m s ->
    weak_pbne nat Nat.eq_dec (types I) nat Nat.eq_dec (fun a b => has_arc I a b = true) (wt I)
              (isgoal I) (Dv W) (start I) (priorq I) (gamma C) (of_w nat nat s)
              (bayes nat (types I) nat Nat.eq_dec (start I) (priorq I) (gamma C)).
Proof.
  intros I P W C h ex H Hc Hcr.
  destruct (decide_read I P W H) as [Hi _].
  unfold decide in H. rewrite Hi in H. simpl in H. rewrite Hc in H.
  destruct (Z.ltb 0 (denominator W)); [| discriminate]. simpl in H.
  destruct (dist_shape_ok I W) eqn:Hshape; [| discriminate]. simpl in H.
  destruct (distances_ok I W) eqn:Hdist; [| discriminate]. simpl in H.
  destruct (reach_ok I W) eqn:Hreach; [| discriminate]. simpl in H.
  rewrite Hcr in H. destruct (has_types W || has_counterexamples W); [discriminate |].
  destruct (wguarantee W) as [[gw |] |] eqn:Hwg; try discriminate.
  destruct (decide_guarantee_spec I W C gw H)
    as [m [mus [tab [HmA [Hm [Hdp [Hh0 [Hcov [Harc [Htab [Hgr HU]]]]]]]]]]].
  destruct (read_profile_spec I Hi P C Hc) as [Hmixlen [Hmix Hrule]].
  split; [exact (distances_exact I W Hi Hdist) |].
  exists gw, m. split; [reflexivity | split; [exact Hm |]].
  intros s Hsd Hsl Hnr2.
  unfold gtable in Htab. destruct (gsteps gw) as [stps |] eqn:Hst; [| discriminate].
  destruct (run_steps I C m stps (mass_trie C) O []) as [[v |] tab0] eqn:Hrun; [discriminate |].
  destruct (Nat.eqb (length stps) (length (mass_trie C))); [| discriminate].
  inversion Htab; subst tab0.
  assert (HA : forall a, In a (normals I C) -> length a = N I) by exact (A_len I C h ex Hcr Hrule).
  assert (Hgh : gh C = h) by exact (gh_h C h ex Hcr).
  assert (Hhl : length h = N I) by exact (h_len I C h ex Hcr Hrule).
  refine (guarantee_pbne (N I) nat Nat.eq_dec (fun a b => has_arc I a b = true) (wt I) (isgoal I) (Dv W)
           (start I) (priorq I) (fun u v Huv => wt_nonneg I Hi u v Huv) (Dv_nonneg I W Hi Hshape Hdist)
           (prior_nonneg I Hi) (gamma C) (gamma_valid I C Hmixlen Hmix)
           (normals I C) (mq I C m) (fun i => nth i h 0) (order I) (order_perm I) s (live I C m)
           _ Hsd Hsl _ (cert C tab) _ _ _).
  - exact (gamma_live I C Hmixlen Hmix h ex Hcr Hrule m stps tab Hrun).
  - intros t Ht l Hl. rewrite <- Hgh. apply Hnr2; [| exact Ht | exact Hl].
    split; [| split].
    + intros i Hi'. apply (first_v_none _ _ Hdp). apply in_seq. lia.
    + apply prem_h; [exact HA | rewrite Hgh; exact Hhl | exact Hh0].
    + exact (prem_arc I C m (gcovers gw) mus Hcov Harc).
  - intros t p l q v u hh Ht Hpl Hq Hqe.
    exact (proj2 (cert_ok I C Hmixlen Hmix h ex Hcr Hrule m stps tab Hrun t p l q v u hh Ht Hpl Hq Hqe)).
  - intros t Ht. unfold types in HU. rewrite forallb_forall in HU. specialize (HU t Ht).
    apply in_seq in Ht. rewrite (Ucert_gU I W C Hmixlen Hmix tab t ltac:(lia)).
    apply Qle_bool_iff in HU. rewrite Hgh in HU. exact HU.
  - intros q v u hh Hon Hqe t t' Ht Ht' Hpos.
    exact (greedy_cert I C Hi Hmixlen Hmix tab Hgr q v u hh Hon Hqe t t' Ht Ht' Hpos).
Qed.
