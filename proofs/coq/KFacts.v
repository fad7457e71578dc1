(** * Facts about the kernel's executable helpers: list equality and
    membership, sums, walks, the trie, the running minimum, and what
    [read_profile] guarantees. *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith.
Import ListNotations.
From DPP Require Import Sums Game Distances Kernel.
Open Scope Q_scope.

Lemma leqb_eq : forall a b, leqb a b = true <-> a = b.
Proof.
  induction a as [| x a IH]; intros [| y b]; simpl; split; intros H; try discriminate; auto.
  - apply andb_true_iff in H as [H1 H2]. apply Nat.eqb_eq in H1. apply IH in H2. subst. reflexivity.
  - inversion H; subst. apply andb_true_iff. split; [apply Nat.eqb_refl | apply IH; reflexivity].
Qed.

Lemma leqb_refl : forall a, leqb a a = true.
Proof. intros a. apply leqb_eq. reflexivity. Qed.

Lemma memb_In : forall p l, memb p l = true <-> In p l.
Proof.
  intros p l. unfold memb. rewrite existsb_exists. split.
  - intros [x [Hx He]]. apply leqb_eq in He. subst. exact Hx.
  - intros H. exists p. split; [exact H | apply leqb_refl].
Qed.

Lemma index_of_nth : forall p l i, index_of p l = Some i -> nth i l [] = p /\ (i < length l)%nat.
Proof.
  intros p. induction l as [| x l IH]; intros i H; simpl in H; [discriminate |].
  destruct (leqb p x) eqn:He.
  - inversion H; subst. apply leqb_eq in He. subst. simpl. split; [reflexivity | lia].
  - destruct (index_of p l) as [j |] eqn:Hj; simpl in H; [| discriminate].
    inversion H; subst. destruct (IH j eq_refl) as [H1 H2]. simpl. split; [exact H1 | lia].
Qed.

Lemma index_of_In : forall p l, In p l -> exists i, index_of p l = Some i.
Proof.
  intros p. induction l as [| x l IH]; intros H; [destruct H |]. simpl.
  destruct (leqb p x) eqn:He; [eexists; reflexivity |].
  destruct H as [-> | H]; [rewrite leqb_refl in He; discriminate |].
  destruct (IH H) as [i Hi]. rewrite Hi. eexists; reflexivity.
Qed.

Lemma index_of_none : forall p l, index_of p l = None -> ~ In p l.
Proof. intros p l H Hin. destruct (index_of_In p l Hin) as [i Hi]. congruence. Qed.

Lemma qsum_sumL : forall (A : Type) (f : A -> Q) l, qsum (map f l) == sumL f l.
Proof. intros A f. induction l as [| x l IH]; simpl; [reflexivity | rewrite IH; reflexivity]. Qed.

Lemma sumL_nth_seq : forall q, sumL (fun t => nth t q 0) (seq 0 (length q)) == qsum q.
Proof.
  intros q. rewrite <- (qsum_sumL nat (fun t => nth t q 0)).
  rewrite (map_nth_seq Q q 0). reflexivity.
Qed.

(** [fold_left add_new]: what it keeps. *)
Lemma add_new_In : forall l acc x, In x (fold_left add_new l acc) <-> In x acc \/ In x l.
Proof.
  induction l as [| y l IH]; intros acc x; simpl; [tauto |].
  rewrite IH. unfold add_new. destruct (memb y acc) eqn:Hm.
  - apply memb_In in Hm. split; [tauto | intros [H | [-> | H]]; auto].
  - rewrite in_app_iff. simpl. tauto.
Qed.

Lemma last_app1 : forall (p : list nat) v d, last (p ++ [v]) d = v.
Proof. intros p v d. induction p as [| x p IH]; [reflexivity |]. simpl. destruct (p ++ [v]) eqn:E; [destruct p; discriminate | exact IH]. Qed.

Lemma last_rev_cons : forall (u : nat) h d, last (rev (u :: h)) d = u.
Proof. intros u h d. simpl. apply last_app1. Qed.

Lemma removelast_app1 : forall (p : list nat) v, removelast (p ++ [v]) = p.
Proof. intros p v. rewrite removelast_app; [simpl; apply app_nil_r | discriminate]. Qed.

(** ** Walks. *)
Section Walks.
  Variable I : instance.
  Notation isgoal := (isgoal I).
  Notation has_arc := (has_arc I).

  Lemma has_arc_wt : forall v u, has_arc v u = true -> In (u, wt I v u) (arcs I v).
  Proof.
    intros v u H. unfold has_arc in H. unfold wt.
    destruct (find (fun a => Nat.eqb (fst a) u) (arcs I v)) as [[x w] |] eqn:F.
    - destruct (find_some _ _ F) as [Hin Heq]. simpl in Heq. apply Nat.eqb_eq in Heq. subst u. exact Hin.
    - apply existsb_exists in H as [[x w] [Hin Heq]].
      pose proof (find_none _ _ F (x, w) Hin) as Hn. simpl in *. congruence.
  Qed.

  Lemma has_arc_In : forall v u w, In (u, w) (arcs I v) -> has_arc v u = true.
  Proof. intros v u w H. apply existsb_exists. exists (u, w). split; [exact H | apply Nat.eqb_refl]. Qed.

  Lemma no_arc_wt : forall v u, has_arc v u = false -> wt I v u == 0.
  Proof.
    intros v u H. unfold wt. destruct (find _ _) as [[x w] |] eqn:F; [| reflexivity].
    destruct (find_some _ _ F) as [Hin Heq]. simpl in Heq. apply Nat.eqb_eq in Heq. subst u.
    rewrite (has_arc_In v x w Hin) in H. discriminate.
  Qed.

  Lemma steps_ok_gwalk : forall l u, steps_ok I u l = true -> isgoal (last (u :: l) O) = true ->
    Game.gwalk nat (fun a b => has_arc a b = true) isgoal u l.
  Proof.
    induction l as [| v l IH]; intros u H Hg; simpl in *; [exact Hg |].
    apply andb_true_iff in H as [H H3]. apply andb_true_iff in H as [H1 H2].
    apply negb_true_iff in H1. split; [exact H1 | split; [exact H2 |]].
    apply IH; [exact H3 |]. destruct l; exact Hg.
  Qed.

  Lemma walk_ok_true : forall w, walk_ok I true w = true ->
    exists l, w = start I :: l /\ Game.gwalk nat (fun a b => has_arc a b = true) isgoal (start I) l /\
              forallb (fun x => Nat.ltb x (n I)) w = true.
  Proof.
    intros [| s l] H; simpl in H; [discriminate |].
    apply andb_true_iff in H as [H Hg]. apply andb_true_iff in H as [H Hs].
    apply andb_true_iff in H as [Hn Heq]. apply Nat.eqb_eq in Heq. subst s.
    exists l. split; [reflexivity | split; [apply steps_ok_gwalk; assumption | exact Hn]].
  Qed.

  Lemma walk_ok_false : forall w, walk_ok I false w = true ->
    exists l, w = start I :: l /\ (1 <= length l)%nat /\ steps_ok I (start I) l = true.
  Proof.
    intros [| s l] H; simpl in H; [discriminate |].
    apply andb_true_iff in H as [H Hl]. apply andb_true_iff in H as [H Hs].
    apply andb_true_iff in H as [_ Heq]. apply Nat.eqb_eq in Heq. subst s.
    exists l. split; [reflexivity | split; [| exact Hs]].
    destruct l; simpl in Hl; [discriminate | simpl; lia].
  Qed.
End Walks.

Lemma nodupb_ok : forall l, nodupb l = true -> NoDup l.
Proof.
  induction l as [| x l IH]; simpl; intros H; constructor.
  - apply andb_true_iff in H as [H _]. apply negb_true_iff in H. intros Hin.
    apply memb_In in Hin. congruence.
  - apply andb_true_iff in H as [_ H]. apply IH. exact H.
Qed.

(** Q helpers. *)
Lemma ltb_lt : forall x y, ltb x y = true <-> x < y.
Proof.
  intros x y. unfold ltb. rewrite negb_true_iff. split.
  - intros H. apply Qnot_le_lt. intros Hc. apply Qle_bool_iff in Hc. congruence.
  - intros H. destruct (Qle_bool y x) eqn:E; [apply Qle_bool_iff in E; lra | reflexivity].
Qed.

Lemma ltb_false : forall x y, ltb x y = false <-> y <= x.
Proof.
  intros x y. unfold ltb. rewrite negb_false_iff. apply Qle_bool_iff.
Qed.

Lemma qsum_nonneg : forall l, (forall x, In x l -> 0 <= x) -> 0 <= qsum l.
Proof.
  induction l as [| x l IH]; intros H; simpl; [lra |].
  pose proof (H x (or_introl eq_refl)). pose proof (IH (fun y Hy => H y (or_intror Hy))). lra.
Qed.
