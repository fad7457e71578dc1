(** * Soundness of the kernel, part 1: what the passing checks say about the
    instance, the profile, the distances and the Defender. *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith.
Import ListNotations.
From DPP Require Import Sums Game Distances Kernel KFacts.
Open Scope Q_scope.

Section Inst.
  Variable I : instance.
  Hypothesis Hi : instance_ok I = true.

  Lemma inst_facts :
    (forall v u w, In (u, w) (nth v (adj I) []) -> 0 < w) /\
    (forall v u w, In (u, w) (nth v (adj I) []) -> (u < n I)%nat) /\
    (start I < n I)%nat /\ (forall g, In g (goals I) -> (g < n I)%nat) /\
    (2 <= N I)%nat /\ length (prior I) = N I /\ (forall b, In b (prior I) -> 0 < b /\ b < 1) /\
    qsum (prior I) == 1.
  Proof.
    unfold instance_ok in Hi. repeat rewrite andb_true_iff in Hi.
    destruct Hi as [[[[[[[[Hadj Hs] Hg] H2] H64] Hnd] Hlen] Hpr] Hsum].
    assert (Hrow : forall v u w, In (u, w) (nth v (adj I) []) -> (u < n I)%nat /\ 0 < w).
    { intros v u w Hin. destruct (Nat.lt_ge_cases v (length (adj I))) as [Hv | Hv].
      - rewrite forallb_forall in Hadj. specialize (Hadj _ (nth_In _ [] Hv)).
        rewrite forallb_forall in Hadj. specialize (Hadj _ Hin). simpl in Hadj.
        apply andb_true_iff in Hadj as [Ha1 Ha2]. apply Nat.ltb_lt in Ha1. apply ltb_lt in Ha2. auto.
      - rewrite nth_overflow in Hin by exact Hv. destruct Hin. }
    split; [intros v u w Hin; apply (Hrow v u w Hin) |].
    split; [intros v u w Hin; apply (Hrow v u w Hin) |].
    split; [apply Nat.ltb_lt; exact Hs |].
    split; [intros g Hin; rewrite forallb_forall in Hg; apply Nat.ltb_lt, Hg, Hin |].
    split; [apply Nat.leb_le; exact H2 |].
    split; [apply Nat.eqb_eq; exact Hlen |].
    split; [| apply Qeq_bool_iff; exact Hsum].
    intros b Hb. rewrite forallb_forall in Hpr. specialize (Hpr b Hb).
    apply andb_true_iff in Hpr as [H1 H3]. apply ltb_lt in H1. apply ltb_lt in H3. auto.
  Qed.

  Lemma w_pos : forall v u w, In (u, w) (nth v (adj I) []) -> 0 < w.
  Proof. apply inst_facts. Qed.
  Lemma tgt_in : forall v u w, In (u, w) (nth v (adj I) []) -> (u < n I)%nat.
  Proof. apply inst_facts. Qed.

  Lemma arc_src : forall v u, has_arc I v u = true -> (v < n I)%nat.
  Proof.
    intros v u H. destruct (Nat.lt_ge_cases v (n I)) as [Hv | Hv]; [exact Hv |].
    unfold has_arc, arcs in H. rewrite nth_overflow in H by exact Hv. discriminate.
  Qed.

  Lemma arc_tgt : forall v u, has_arc I v u = true -> (u < n I)%nat.
  Proof. intros v u H. exact (tgt_in v u _ (has_arc_wt I v u H)). Qed.

  Lemma wt_pos : forall v u, has_arc I v u = true -> 0 < wt I v u.
  Proof. intros v u H. exact (w_pos v u _ (has_arc_wt I v u H)). Qed.

  Lemma wt_nonneg : forall v u, has_arc I v u = true -> 0 <= wt I v u.
  Proof. intros v u H. pose proof (wt_pos v u H). lra. Qed.

  Lemma prior_nonneg : forall t, 0 <= priorq I t.
  Proof.
    intros t. unfold priorq. destruct (Nat.lt_ge_cases t (length (prior I))) as [Ht | Ht].
    - destruct inst_facts as [_ [_ [_ [_ [_ [_ [Hb _]]]]]]].
      pose proof (Hb _ (nth_In _ 0 Ht)). lra.
    - rewrite nth_overflow by exact Ht. lra.
  Qed.

  Lemma goal_index : forall g, In g (goals I) -> exists j, (j < N I)%nat /\ goal I j = g.
  Proof.
    intros g Hg. destruct (In_nth _ _ O Hg) as [j [Hj Heq]]. exists j. split; [exact Hj | exact Heq].
  Qed.

  Lemma isgoal_In : forall v, isgoal I v = true -> In v (goals I).
  Proof.
    intros v H. unfold isgoal in H. apply existsb_exists in H as [g [Hg He]].
    apply Nat.eqb_eq in He. subst. exact Hg.
  Qed.
End Inst.

(** ** What [read_profile] guarantees. *)
Section Read.
  Variable I : instance.
  Hypothesis Hi : instance_ok I = true.

  Lemma dist_two : forall j p, N I = 2%nat -> prob_ok p = true -> dist_ok I (two j p) = true.
  Proof.
    intros j p HN Hp. unfold prob_ok in Hp. apply andb_true_iff in Hp as [H0 H1].
    apply Qle_bool_iff in H0. apply Qle_bool_iff in H1.
    unfold dist_ok, two. rewrite HN.
    destruct (Nat.eqb j O); simpl; repeat (apply andb_true_iff; split);
      try apply Qle_bool_iff; try apply Qeq_bool_iff; try reflexivity; try lra.
  Qed.

  Definition rule_ok (r : rule) : Prop :=
    match r with
    | RTable es d g =>
        (forall e, In e es -> walk_ok I false (fst e) = true /\ dist_ok I (snd e) = true) /\
        (g < N I)%nat /\
        match d with DDist q => dist_ok I q = true | DProgress => N I = 2%nat | DNone => True end
    | RGuarantee h ex => length h = N I /\ (forall a, In a ex -> length a = N I)
    end.

  Lemma read_profile_spec : forall P C, read_profile I P = Some C ->
    length (mix C) = N I /\ (forall m, In m (mix C) -> mixture_ok I m = true) /\ rule_ok (crule C).
  Proof.
    destruct (inst_facts I Hi) as [_ [_ [_ [_ [HN2 _]]]]].
    intros [p | p] C H; unfold read_profile in H.
    - destruct (match ngoals p with Some gs => negb (leqb gs (goals I)) | None => false end); [discriminate |].
      destruct (negb (Nat.eqb (length (nmix p)) (N I)) || negb (forallb (mixture_ok I) (nmix p))) eqn:Hm;
        [discriminate |].
      apply orb_false_iff in Hm as [Hl Hm]. apply negb_false_iff in Hl, Hm.
      apply Nat.eqb_eq in Hl. rewrite forallb_forall in Hm.
      destruct (nrule p) as [es d g | h ex] eqn:Hr.
      + destruct (negb (entries_ok I es)) eqn:He; [discriminate |]. apply negb_false_iff in He.
        unfold entries_ok in He. apply andb_true_iff in He as [He _]. rewrite forallb_forall in He.
        assert (Hes : forall e, In e es -> walk_ok I false (fst e) = true /\ dist_ok I (snd e) = true)
          by (intros e Hin; apply andb_true_iff, He, Hin).
        destruct d as [| q |]; [| destruct (dist_ok I q) eqn:Hq |]; try discriminate;
          inversion H; subst; simpl; (split; [exact Hl | split; [exact Hm |]]);
          (split; [exact Hes | split; [lia | auto]]).
      + destruct (Nat.eqb (length h) (N I) && forallb (fun a => Nat.eqb (length a) (N I)) ex) eqn:Hh;
          [| discriminate].
        apply andb_true_iff in Hh as [Hh Hex]. rewrite forallb_forall in Hex.
        inversion H; subst. simpl. apply Nat.eqb_eq in Hh.
        split; [exact Hl | split; [exact Hm | split; [exact Hh |]]].
        intros a Ha. apply Nat.eqb_eq, Hex, Ha.
    - destruct (find_index (tprimary p) (goals I)) as [first |] eqn:Hf; [| discriminate].
      destruct (find_index (tsecondary p) (goals I)) as [second |] eqn:Hs; [| discriminate].
      destruct (Nat.eqb first second || negb (Nat.eqb (N I) 2)) eqn:Hfs; [discriminate |].
      apply orb_false_iff in Hfs as [_ HN]. apply negb_false_iff, Nat.eqb_eq in HN.
      destruct (ltb (priorq I first) (priorq I (1 - first))); [discriminate |].
      destruct (negb (mixture_ok I (tmix_primary p) && mixture_ok I (tmix_secondary p))) eqn:Hm;
        [discriminate |].
      apply negb_false_iff, andb_true_iff in Hm as [Hm1 Hm2].
      assert (Hmix : forall mixes, mixes = [tmix_primary p; tmix_secondary p] \/
                                   mixes = [tmix_secondary p; tmix_primary p] ->
                     length mixes = N I /\ (forall m, In m mixes -> mixture_ok I m = true)).
      { intros mixes [-> | ->]; (split; [simpl; lia |]);
          intros m [<- | [<- | []]]; assumption. }
      destruct (find_index (trgoal p) (goals I)) as [j |] eqn:Hj; [| discriminate].
      assert (Hjlt : (j < N I)%nat).
      { clear -Hj. unfold N. revert j Hj. induction (goals I) as [| x l IH]; intros j Hj; simpl in Hj;
          [discriminate |]. destruct (Nat.eqb x (trgoal p)); [inversion Hj; simpl; lia |].
        destruct (find_index (trgoal p) l) as [k |]; simpl in Hj; [| discriminate].
        inversion Hj; subst. simpl. pose proof (IH k eq_refl). lia. }
      set (mixes := if Nat.eqb first O then [tmix_primary p; tmix_secondary p]
                    else [tmix_secondary p; tmix_primary p]) in H.
      assert (Hmx : length mixes = N I /\ (forall m, In m mixes -> mixture_ok I m = true)).
      { apply Hmix. unfold mixes. destruct (Nat.eqb first O); auto. }
      destruct Hmx as [Hml Hmo].
      destruct (trule p) as [| es d |]; [| | discriminate].
      + inversion H; subst. simpl. split; [exact Hml | split; [exact Hmo |]].
        split; [intros e [] | split; [exact Hjlt | exact HN]].
      + destruct (negb (forallb (fun e => walk_ok I false (fst e) && prob_ok (snd e)) es &&
                        nodupb (map fst es))) eqn:He; [discriminate |].
        apply negb_false_iff, andb_true_iff in He as [He _]. rewrite forallb_forall in He.
        assert (Hes : forall e, In e (map (fun e => (fst e, two j (snd e))) es) ->
                                walk_ok I false (fst e) = true /\ dist_ok I (snd e) = true).
        { intros e Hin. apply in_map_iff in Hin as [e0 [<- Hin]]. simpl.
          pose proof (He e0 Hin) as He0. apply andb_true_iff in He0 as [H1 H2].
          split; [exact H1 | apply dist_two; assumption]. }
        destruct d as [| | q]; [| | destruct (prob_ok q) eqn:Hq; [| discriminate]];
          inversion H; subst; simpl; (split; [exact Hml | split; [exact Hmo |]]);
          (split; [exact Hes | split; [exact Hjlt |]]); auto.
        apply dist_two; assumption.
  Qed.
End Read.
