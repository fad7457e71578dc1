(** * Soundness of the kernel, part 2: the distances are exact, every node of
    a game walk is alive, and the table Defender is a distribution at every
    history. *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith.
Import ListNotations.
From DPP Require Import Sums Game Distances Kernel KFacts KSound1.
Open Scope Q_scope.

Section Dist.
  Variable I : instance.
  Variable W : witness.
  Hypothesis Hi : instance_ok I = true.
  Hypothesis Hshape : dist_shape_ok I W = true.
  Hypothesis Hdist : distances_ok I W = true.
  Hypothesis Hreach : reach_ok I W = true.

  Notation D := (D W).
  Notation E := (fun a b => has_arc I a b = true).

  Lemma bell : forall j, (j < N I)%nat -> bellman_ok (adj I) (goal I j) (D j) = true.
  Proof.
    intros j Hj. unfold distances_ok in Hdist. rewrite forallb_forall in Hdist.
    apply Hdist. unfold types. apply in_seq. lia.
  Qed.

  Lemma D_out : forall j v, (n I <= v)%nat \/ (N I <= j)%nat -> D j v = None.
  Proof.
    intros j v Hjv. unfold Kernel.D, dlists.
    unfold dist_shape_ok in Hshape. destruct (distances W) as [l |]; [| discriminate].
    apply andb_true_iff in Hshape as [Hl Hall]. apply Nat.eqb_eq in Hl.
    rewrite forallb_forall in Hall.
    destruct (Nat.lt_ge_cases j (length l)) as [Hj | Hj].
    - destruct Hjv as [Hv | Hj']; [| lia].
      pose proof (Hall _ (nth_In _ [] Hj)) as Hn. apply Nat.eqb_eq in Hn.
      rewrite (nth_overflow (nth j l [])) by lia. reflexivity.
    - rewrite (nth_overflow l) by exact Hj. destruct v; reflexivity.
  Qed.

  Lemma D_some_in : forall j v x, D j v = Some x -> (v < n I)%nat /\ (j < N I)%nat.
  Proof.
    intros j v x H. destruct (Nat.lt_ge_cases v (n I)), (Nat.lt_ge_cases j (N I)); auto;
      rewrite D_out in H by auto; discriminate.
  Qed.

  Lemma reach_at : forall j v, (j < N I)%nat -> In v (start I :: goals I) -> exists x, D j v = Some x.
  Proof.
    intros j v Hj Hv. unfold reach_ok in Hreach. rewrite forallb_forall in Hreach.
    assert (Hjt : In j (types I)) by (unfold types; apply in_seq; lia).
    specialize (Hreach j Hjt). rewrite forallb_forall in Hreach. specialize (Hreach v Hv).
    destruct (D j v) as [x |]; [exists x; reflexivity | discriminate].
  Qed.

  Lemma Dv_nonneg : forall t g, 0 <= Dv W t g.
  Proof.
    intros t g. unfold Dv. destruct (D t g) as [x |] eqn:Hx; [| lra].
    destruct (D_some_in t g x Hx) as [Hg Ht].
    exact (label_nonneg (adj I) (w_pos I Hi) (tgt_in I Hi) _ _ (bell t Ht) g x Hg Hx).
  Qed.

  Lemma Dv_some : forall t g x, D t g = Some x -> Dv W t g = x.
  Proof. intros t g x H. unfold Dv. rewrite H. reflexivity. Qed.

  (** K.1 for every goal. *)
  Theorem distances_exact : forall j v, (j < N I)%nat -> (v < n I)%nat ->
    is_distance (adj I) (goal I j) v (D j v).
  Proof.
    intros j v Hj Hv. exact (bellman_exact (adj I) (w_pos I Hi) (tgt_in I Hi) _ _ (bell j Hj) v Hv).
  Qed.

  (** Every node of a game walk reaches a goal: it is alive. *)
  Fixpoint to_path (u : nat) (l : list nat) : list (nat * Q) :=
    match l with [] => [] | v :: l' => (v, wt I u v) :: to_path v l' end.

  Lemma gwalk_apath : forall l u, gwalk nat E (isgoal I) u l -> apath (adj I) (last (u :: l) O) u (to_path u l).
  Proof.
    induction l as [| v l IH]; intros u H; simpl in *; [reflexivity |].
    destruct H as [_ [Huv H]]. split; [exact (has_arc_wt I u v Huv) |].
    specialize (IH v H). destruct l; exact IH.
  Qed.

  Lemma gwalk_alive : forall l u, gwalk nat E (isgoal I) u l -> (u < n I)%nat -> alive I W u = true.
  Proof.
    intros l u H Hu.
    assert (Hg : isgoal I (last (u :: l) O) = true).
    { clear Hu. revert u H. induction l as [| v l IH]; intros u H; simpl in *; [exact H |].
      destruct H as [_ [_ H]]. specialize (IH v H). destruct l; exact IH. }
    destruct (goal_index I _ (isgoal_In I _ Hg)) as [j [Hj Hgj]].
    pose proof (gwalk_apath l u H) as Hp. rewrite <- Hgj in Hp.
    destruct (label_le_path (adj I) (w_pos I Hi) (tgt_in I Hi) _ _ (bell j Hj) _ u Hu Hp) as [x [Hx _]].
    unfold alive. apply existsb_exists. exists j. split; [unfold types; apply in_seq; lia | rewrite Hx; reflexivity].
  Qed.

  Lemma gwalk_all_alive : forall l u, gwalk nat E (isgoal I) u l -> (u < n I)%nat ->
    forall x, In x (u :: l) -> alive I W x = true /\ (x < n I)%nat.
  Proof.
    induction l as [| v l IH]; intros u H Hu x Hx.
    - destruct Hx as [<- | []]. split; [exact (gwalk_alive [] u H Hu) | exact Hu].
    - destruct Hx as [<- | Hx]; [split; [exact (gwalk_alive _ u H Hu) | exact Hu] |].
      destruct H as [Hng [Huv H]].
      exact (IH v H (arc_tgt I Hi u v Huv) x Hx).
  Qed.
End Dist.

(** ** The table Defender as a strategy of the game. *)
Section Defender.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Hypothesis Hi : instance_ok I = true.
  Hypothesis Hshape : dist_shape_ok I W = true.
  Hypothesis Hdist : distances_ok I W = true.
  Hypothesis Hreach : reach_ok I W = true.
  Hypothesis Hrule : rule_ok I (crule C).
  Variables (es : list (list nat * list Q)) (dflt : default) (gl : nat).
  Hypothesis Hcr : crule C = RTable es dflt gl.

  Notation D := (D W).

  (** Where the table is undefined (never on a walk of the game, once the
      kernel accepts) the Defender puts the weight on the first goal. *)
  Definition e0 (t : nat) : Q := if Nat.eqb t O then 1 else 0.

  Definition gsig (p : list nat) (v t : nat) : Q :=
    match sigma I W C p v with Some q => nth t q 0 | None => e0 t end.

  Definition defender : wstrat nat nat := fun h u v t => gsig (rev (u :: h)) v t.

  Lemma gsig_defined : forall p v t q, sigma I W C p v = Some q -> gsig p v t = sig_t I W C p v t.
  Proof. intros p v t q H. unfold gsig, sig_t. rewrite H. reflexivity. Qed.

  Lemma tgoal_lt : (tgoal C < N I)%nat.
  Proof. unfold tgoal. rewrite Hcr. unfold rule_ok in Hrule. rewrite Hcr in Hrule. apply Hrule. Qed.

  Lemma cmin_app1 : forall p v, cmin W C (p ++ [v]) = omin (cmin W C p) (D (tgoal C) v).
  Proof. intros p v. unfold cmin. rewrite fold_left_app. reflexivity. Qed.

  Lemma omin_le_r : forall a y, exists c, omin a (Some y) = Some c /\ c <= y.
  Proof.
    intros [x |] y; simpl; [| exists y; split; [reflexivity | lra]].
    destruct (Qle_bool x y) eqn:E; eexists; split; try reflexivity.
    - apply Qle_bool_iff. exact E.
    - lra.
  Qed.

  Lemma omin_le_l : forall x b, exists c, omin (Some x) b = Some c /\ c <= x.
  Proof.
    intros x [y |]; simpl; [| exists x; split; [reflexivity | lra]].
    destruct (Qle_bool x y) eqn:E; eexists; split; try reflexivity; try lra.
    assert (Hn : ~ (x <= y)) by (intros Hc; apply Qle_bool_iff in Hc; congruence).
    apply Qnot_le_lt in Hn. lra.
  Qed.

  Lemma cmin_le_last : forall p du, p <> [] -> D (tgoal C) (last p O) = Some du ->
    exists c, cmin W C p = Some c /\ c <= du.
  Proof.
    intros p du Hp Hd. destruct (exists_last Hp) as [p' [v ->]].
    rewrite last_app1 in Hd. rewrite cmin_app1, Hd. apply omin_le_r.
  Qed.

  Lemma cmin_start : forall l, exists c, cmin W C (start I :: l) = Some c.
  Proof.
    intros l.
    destruct (reach_at I W Hreach (tgoal C) (start I) tgoal_lt (or_introl eq_refl)) as [d0 Hd0].
    unfold cmin. cbn [fold_left].
    replace (omin None (D (tgoal C) (start I))) with (Some d0) by (rewrite Hd0; reflexivity).
    generalize d0. induction l as [| x l IH]; intros d; cbn [fold_left]; [eexists; reflexivity |].
    destruct (omin_le_l d (D (tgoal C) x)) as [c [Hc _]]. rewrite Hc. apply IH.
  Qed.

  Lemma qdiv_0 : forall x, x / 0 == 0.
  Proof. intros x. unfold Qdiv. setoid_replace (/ 0) with 0 by reflexivity. ring. Qed.

  (** The progress rule's probability lies in [0, 1] (TEL.1), on every arc
      and trivially elsewhere. *)
  Lemma prog_range : forall p v, 0 <= prog I W C p v <= 1.
  Proof.
    intros p v. unfold prog.
    destruct (cmin W C p) as [c |] eqn:Hc; [| lra].
    destruct (D (tgoal C) v) as [d |] eqn:Hd; [| lra].
    destruct (Qle_bool c d) eqn:Hcd; [lra |].
    assert (Hlt : d < c) by (apply Qnot_le_lt; intros Hc'; apply Qle_bool_iff in Hc'; congruence).
    set (u := last p O).
    destruct (has_arc I u v) eqn:Ha.
    2: { rewrite (no_arc_wt I u v Ha), qdiv_0. lra. }
    pose proof (wt_pos I Hi u v Ha) as Hw.
    assert (Hp : p <> []) by (intros ->; discriminate).
    destruct (D_some_in I W Hshape _ _ _ Hd) as [Hv _].
    pose proof (label_nonneg (adj I) (w_pos I Hi) (tgt_in I Hi) _ _ (bell I W Hdist _ tgoal_lt) v d Hv Hd) as Hd0.
    destruct (Nat.eq_dec u (goal I (tgoal C))) as [Hug | Hug].
    - exfalso. destruct (label_goal _ _ _ (bell I W Hdist _ tgoal_lt)) as [z [Hz Hz0]].
      rewrite <- Hug in Hz. destruct (cmin_le_last p z Hp Hz) as [c' [Hc' Hle]].
      rewrite Hc in Hc'. inversion Hc'; subst c'. lra.
    - destruct (label_arc _ _ _ (bell I W Hdist _ tgoal_lt) u v (wt I u v) d (arc_src I u v Ha) Hug
                  (has_arc_wt I u v Ha) Hd) as [du [Hdu Hle]].
      destruct (cmin_le_last p du Hp Hdu) as [c' [Hc' Hcdu]]. rewrite Hc in Hc'. inversion Hc'; subst c'.
      split.
      + apply Qle_shift_div_l; [exact Hw | lra].
      + apply Qle_shift_div_r; [exact Hw | lra].
  Qed.

  Lemma dist_ok_dist : forall q, dist_ok I q = true -> dist nat (types I) (fun t => nth t q 0).
  Proof.
    intros q Hq. unfold dist_ok in Hq. apply andb_true_iff in Hq as [Hq Hs].
    apply andb_true_iff in Hq as [Hl Hr]. apply Nat.eqb_eq in Hl. apply Qeq_bool_iff in Hs.
    rewrite forallb_forall in Hr. split.
    - intros t. destruct (Nat.lt_ge_cases t (length q)) as [Ht | Ht].
      + pose proof (Hr _ (nth_In _ 0 Ht)) as H. apply andb_true_iff in H as [H _]. apply Qle_bool_iff. exact H.
      + rewrite nth_overflow by exact Ht. lra.
    - unfold types. rewrite <- Hl, sumL_nth_seq. exact Hs.
  Qed.

  Lemma lookup_entry : forall p q, lookup C p = Some q -> exists e, In e (tentries C) /\ fst e = p /\ snd e = q.
  Proof.
    intros p q H. unfold lookup in H.
    destruct (find (fun e => leqb (fst e) p) (tentries C)) as [e |] eqn:F; [| discriminate].
    simpl in H. inversion H; subst. destruct (find_some _ _ F) as [Hin He].
    apply leqb_eq in He. exists e. auto.
  Qed.

  Lemma tentries_ok : forall e, In e (tentries C) -> walk_ok I false (fst e) = true /\ dist_ok I (snd e) = true.
  Proof.
    intros e He. unfold tentries in He. rewrite Hcr in He. unfold rule_ok in Hrule. rewrite Hcr in Hrule.
    apply Hrule. exact He.
  Qed.

  Theorem gsig_dist : forall p v, dist nat (types I) (gsig p v).
  Proof.
    destruct (inst_facts I Hi) as [_ [_ [_ [_ [HN2 _]]]]].
    intros p v. pose proof (prog_range p v) as Hr. pose proof tgoal_lt as Htg. unfold gsig, sigma.
    destruct (lookup C (p ++ [v])) as [q |] eqn:Hl.
    - destruct (lookup_entry _ _ Hl) as [e [He [_ <-]]]. apply dist_ok_dist, (tentries_ok e He).
    - unfold tdefault. rewrite Hcr. pose proof Hrule as Hru. unfold rule_ok in Hru. rewrite Hcr in Hru.
      destruct Hru as [_ [Hgl Hd]].
      destruct dflt as [| q |].
      + split.
        * intros t. unfold e0. destruct (Nat.eqb t O); lra.
        * unfold types. destruct (N I) as [| N'] eqn:HN; [lia |]. simpl.
          rewrite sumL_zero; [unfold e0; simpl; ring |]. intros t Ht. apply in_seq in Ht. unfold e0.
          destruct (Nat.eqb t O) eqn:E; [apply Nat.eqb_eq in E; lia | reflexivity].
      + apply dist_ok_dist. exact Hd.
      + unfold tgoal in Htg |- *. rewrite Hcr in Htg |- *. unfold types. rewrite Hd.
        set (x := prog I W C p v) in *. split.
        * intros t. destruct t as [| [| t]]; cbn [nth map seq];
            [destruct (Nat.eqb 0 gl) | destruct (Nat.eqb 1 gl) | destruct t; cbn [nth]]; lra.
        * rewrite Hd in Hgl. assert (Hg2 : gl = O \/ gl = 1%nat) by lia.
          destruct Hg2 as [Hg | Hg]; rewrite Hg; simpl; ring.
  Qed.

  Lemma defender_dist : forall h u v, dist nat (types I) (defender h u v).
  Proof. intros h u v. apply gsig_dist. Qed.
End Defender.
