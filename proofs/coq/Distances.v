(** * K.1: distance labels that satisfy Bellman's equation are the exact
    shortest-path distances.

    The graph is an adjacency list [adj] over the nodes [0 .. length adj - 1]
    ([adj[v]] lists the arcs [(u, w)] of [v]); a label is [Some x] or [None]
    (+∞).  [bellman_ok] is the kernel's test for the labels [D] of goal [g]:
    [D g = 0] and [D v = min over the arcs (v, u) of w + D u] at every other
    node.  [bellman_exact]: with positive weights, [D v] is then the least
    length of a path from [v] to [g] ([None] exactly when there is none). *)

From Coq Require Import QArith Lqa List Arith Lia Bool.
Import ListNotations.
From DPP Require Import Sums.
Open Scope Q_scope.

(** ** Options of rationals: +∞ is [None]. *)
Definition oplus (w : Q) (y : option Q) : option Q :=
  match y with Some y => Some (w + y) | None => None end.

Definition omin (a b : option Q) : option Q :=
  match a, b with
  | None, _ => b
  | _, None => a
  | Some x, Some y => Some (if Qle_bool x y then x else y)
  end.

Definition oeq (a b : option Q) : bool :=
  match a, b with
  | Some x, Some y => Qeq_bool x y
  | None, None => true
  | _, _ => false
  end.

(** [relax D row]: the least [w + D u] over the arcs [(u, w)] of [row]. *)
Definition relax (D : nat -> option Q) (row : list (nat * Q)) : option Q :=
  fold_right (fun a acc => omin (oplus (snd a) (D (fst a))) acc) None row.

Definition bellman_ok (adj : list (list (nat * Q))) (g : nat) (D : nat -> option Q) : bool :=
  Nat.ltb g (length adj) &&
  forallb (fun v => if Nat.eqb v g then oeq (D v) (Some 0) else oeq (D v) (relax D (nth v adj [])))
          (seq 0 (length adj)).

Lemma oeq_some : forall a y, oeq a (Some y) = true -> exists x, a = Some x /\ x == y.
Proof.
  intros [x |] y H; simpl in H; [| discriminate].
  exists x. split; [reflexivity | apply Qeq_bool_iff; exact H].
Qed.

Lemma oeq_sym_some : forall a b x, oeq a b = true -> b = Some x -> exists y, a = Some y /\ y == x.
Proof. intros a b x H ->. apply oeq_some. exact H. Qed.

Lemma oeq_none : forall a b, oeq a b = true -> b = None -> a = None.
Proof. intros [x |] b H ->; [discriminate | reflexivity]. Qed.

Lemma relax_le : forall D row u w y, In (u, w) row -> D u = Some y ->
  exists r, relax D row = Some r /\ r <= w + y.
Proof.
  intros D. induction row as [| [u' w'] row IH]; intros u w y Hin Hy; [destruct Hin |].
  simpl. destruct Hin as [Heq | Hin].
  - inversion Heq; subst. rewrite Hy. simpl.
    destruct (relax D row) as [r |]; simpl.
    + destruct (Qle_bool (w + y) r) eqn:Hle.
      * exists (w + y). split; [reflexivity | lra].
      * exists r. split; [reflexivity |].
        assert (Hn : ~ (w + y <= r)) by (intros Hc; apply Qle_bool_iff in Hc; rewrite Hc in Hle; discriminate).
        apply Qnot_le_lt in Hn. lra.
    + exists (w + y). split; [reflexivity | lra].
  - destruct (IH u w y Hin Hy) as [r [Hr Hle]]. rewrite Hr.
    destruct (oplus w' (D u')) as [z |]; simpl.
    + destruct (Qle_bool z r) eqn:Hz; eexists; split; try reflexivity.
      * apply Qle_bool_iff in Hz. lra.
      * exact Hle.
    + exists r. auto.
Qed.

Lemma relax_attained : forall D row r, relax D row = Some r ->
  exists u w y, In (u, w) row /\ D u = Some y /\ r == w + y.
Proof.
  intros D. induction row as [| [u w] row IH]; intros r H; simpl in H; [discriminate |].
  destruct (D u) as [y |] eqn:Hu; simpl in H.
  - destruct (relax D row) as [r' |] eqn:Hr.
    + destruct (Qle_bool (w + y) r'); inversion H; subst.
      * exists u, w, y. split; [left; reflexivity | split; [exact Hu | reflexivity]].
      * destruct (IH r eq_refl) as [u' [w' [y' [Hin [Hu' Heq]]]]].
        exists u', w', y'. split; [right; exact Hin | split; [exact Hu' | exact Heq]].
    + inversion H; subst. exists u, w, y. split; [left; reflexivity | split; [exact Hu | reflexivity]].
  - destruct (IH r H) as [u' [w' [y' [Hin [Hu' Heq]]]]].
    exists u', w', y'. split; [right; exact Hin | split; [exact Hu' | exact Heq]].
Qed.

Lemma relax_none : forall D row u w, relax D row = None -> In (u, w) row -> D u = None.
Proof.
  intros D row u w H Hin. destruct (D u) as [y |] eqn:Hu; [| reflexivity].
  destruct (relax_le D row u w y Hin Hu) as [r [Hr _]]. rewrite Hr in H. discriminate.
Qed.

Section Exact.
  Variable adj : list (list (nat * Q)).
  Let n := length adj.
  Hypothesis w_pos : forall v u w, In (u, w) (nth v adj []) -> 0 < w.
  Hypothesis tgt_in : forall v u w, In (u, w) (nth v adj []) -> (u < n)%nat.
  Variable g : nat.
  Variable D : nat -> option Q.
  Hypothesis Hb : bellman_ok adj g D = true.

  (** Paths of the full graph (through goals or not) from [v] to [g]. *)
  Fixpoint apath (v : nat) (l : list (nat * Q)) : Prop :=
    match l with
    | [] => v = g
    | (u, w) :: l' => In (u, w) (nth v adj []) /\ apath u l'
    end.

  Fixpoint plen (l : list (nat * Q)) : Q :=
    match l with [] => 0 | (_, w) :: l' => w + plen l' end.

  Lemma g_lt : (g < n)%nat.
  Proof. unfold bellman_ok in Hb. apply andb_true_iff in Hb as [H _]. apply Nat.ltb_lt. exact H. Qed.

  Lemma eq_at : forall v, (v < n)%nat ->
    (v = g /\ oeq (D v) (Some 0) = true) \/ (v <> g /\ oeq (D v) (relax D (nth v adj [])) = true).
  Proof.
    intros v Hv. unfold bellman_ok in Hb. apply andb_true_iff in Hb as [_ H].
    rewrite forallb_forall in H. specialize (H v (proj2 (in_seq _ _ _) (conj (Nat.le_0_l v) Hv))).
    destruct (Nat.eqb v g) eqn:Hvg; [left; apply Nat.eqb_eq in Hvg; auto | right; apply Nat.eqb_neq in Hvg; auto].
  Qed.

  Lemma plen_nonneg : forall v l, apath v l -> 0 <= plen l.
  Proof.
    intros v l. revert v. induction l as [| [u w] l IH]; intros v Hp; simpl in *; [lra |].
    destruct Hp as [Hin Hp]. pose proof (w_pos v u w Hin). pose proof (IH u Hp). lra.
  Qed.

  (** The lower bound: a path makes the label finite and at most its length. *)
  Theorem label_le_path : forall l v, (v < n)%nat -> apath v l -> exists x, D v = Some x /\ x <= plen l.
  Proof.
    induction l as [| [u w] l IH]; intros v Hv Hp; simpl in Hp.
    - subst v. destruct (eq_at g g_lt) as [[_ H] | [Hn _]]; [| contradiction].
      destruct (oeq_some _ _ H) as [x [Hx Hx0]]. exists x. simpl. split; [exact Hx | lra].
    - destruct Hp as [Hin Hp].
      destruct (IH u (tgt_in v u w Hin) Hp) as [y [Hy Hle]].
      pose proof (plen_nonneg u l Hp) as Hpl. pose proof (w_pos v u w Hin) as Hwp.
      destruct (eq_at v Hv) as [[-> Heq] | [_ Heq]].
      + destruct (oeq_some _ _ Heq) as [x [Hx Hx0]]. exists x. simpl. split; [exact Hx | lra].
      + destruct (relax_le D _ u w y Hin Hy) as [r [Hr Hrle]].
        destruct (oeq_sym_some _ _ _ Heq Hr) as [x [Hx Hxr]].
        exists x. simpl. split; [exact Hx | lra].
  Qed.

  Definition below (x : Q) : nat :=
    length (filter (fun z => match D z with Some y => negb (Qle_bool x y) | None => false end) (seq 0 n)).

  Lemma filter_lt : forall (f h : nat -> bool) l z,
    (forall y, In y l -> f y = true -> h y = true) -> In z l -> h z = true -> f z = false ->
    (length (filter f l) < length (filter h l))%nat.
  Proof.
    intros f h. induction l as [| y l IH]; intros z Hfh Hz Hh Hf; [destruct Hz |].
    simpl. destruct Hz as [-> | Hz].
    - rewrite Hf, Hh. simpl.
      assert (length (filter f l) <= length (filter h l))%nat; [| lia].
      clear IH. induction l as [| y l IH']; simpl; [lia |].
      destruct (f y) eqn:Hy.
      + rewrite (Hfh y (or_intror (or_introl eq_refl)) Hy). simpl.
        assert (length (filter f l) <= length (filter h l))%nat; [| lia].
        apply IH'. intros x Hx Hfx. apply Hfh; [destruct Hx as [<- | Hx]; [left; reflexivity | right; right; exact Hx] | exact Hfx].
      + destruct (h y); simpl; [| apply IH'].
        * assert (length (filter f l) <= length (filter h l))%nat; [| lia].
          apply IH'. intros x Hx Hfx. apply Hfh; [destruct Hx as [<- | Hx]; [left; reflexivity | right; right; exact Hx] | exact Hfx].
        * intros x Hx Hfx. apply Hfh; [destruct Hx as [<- | Hx]; [left; reflexivity | right; right; exact Hx] | exact Hfx].
    - assert (IHl : (length (filter f l) < length (filter h l))%nat)
        by (apply (IH z); auto; intros x Hx Hfx; apply Hfh; [right; exact Hx | exact Hfx]).
      destruct (f y) eqn:Hy.
      + rewrite (Hfh y (or_introl eq_refl) Hy). simpl. lia.
      + destruct (h y); simpl; lia.
  Qed.

  (** The upper bound: a finite label is the length of a path. *)
  Theorem path_of_label : forall v x, (v < n)%nat -> D v = Some x -> exists l, apath v l /\ plen l == x.
  Proof.
    intros v x. remember (below x) as k eqn:Hk. revert v x Hk.
    induction k as [k IH] using lt_wf_ind. intros v x Hk Hv Hx.
    destruct (eq_at v Hv) as [[-> H] | [Hvg H]].
    - exists []. simpl. split; [reflexivity |].
      destruct (oeq_some _ _ H) as [x' [Hx' H0]]. rewrite Hx in Hx'. inversion Hx'; subst. lra.
    - destruct (relax D (nth v adj [])) as [r |] eqn:Hr.
      2: { rewrite (oeq_none _ _ H eq_refl) in Hx. discriminate. }
      destruct (oeq_some _ _ H) as [x' [Hx' Hxr]]. rewrite Hx in Hx'. inversion Hx'; subst x'.
      destruct (relax_attained D _ r Hr) as [u [w [y [Hin [Hy Hry]]]]].
      pose proof (w_pos v u w Hin) as Hw. pose proof (tgt_in v u w Hin) as Hu.
      assert (Hlt : (below y < below x)%nat).
      { unfold below. apply (filter_lt _ _ _ u).
        - intros z _. destruct (D z) as [yz |]; [| discriminate].
          intros Hz. apply negb_true_iff in Hz. apply negb_true_iff.
          destruct (Qle_bool x yz) eqn:Hxz; [| reflexivity].
          apply Qle_bool_iff in Hxz.
          assert (Hn : ~ (y <= yz)) by (intros Hc; apply Qle_bool_iff in Hc; rewrite Hc in Hz; discriminate).
          apply Qnot_le_lt in Hn. lra.
        - apply in_seq. lia.
        - rewrite Hy. apply negb_true_iff.
          destruct (Qle_bool x y) eqn:Hxy; [| reflexivity]. apply Qle_bool_iff in Hxy. lra.
        - rewrite Hy. apply negb_false_iff. apply Qle_bool_iff. lra. }
      destruct (IH (below y) ltac:(lia) u y eq_refl Hu Hy) as [l [Hp Hl]].
      exists ((u, w) :: l). simpl. split; [auto | lra].
  Qed.

  (** K.1: the labels are the shortest-path distances to [g]. *)
  Definition is_distance (v : nat) (d : option Q) : Prop :=
    (forall l, apath v l -> exists x, d = Some x /\ x <= plen l) /\
    (forall x, d = Some x -> exists l, apath v l /\ plen l == x).

  Theorem bellman_exact : forall v, (v < n)%nat -> is_distance v (D v).
  Proof.
    intros v Hv. split.
    - intros l Hp. exact (label_le_path l v Hv Hp).
    - intros x Hx. exact (path_of_label v x Hv Hx).
  Qed.

  Corollary label_nonneg : forall v x, (v < n)%nat -> D v = Some x -> 0 <= x.
  Proof.
    intros v x Hv Hx. destruct (path_of_label v x Hv Hx) as [l [Hp Hl]].
    pose proof (plen_nonneg v l Hp). lra.
  Qed.

  (** The triangle inequality along an arc from a node other than [g]. *)
  Corollary label_arc : forall v u w y, (v < n)%nat -> v <> g -> In (u, w) (nth v adj []) -> D u = Some y ->
    exists x, D v = Some x /\ x <= w + y.
  Proof.
    intros v u w y Hv Hvg Hin Hy.
    destruct (eq_at v Hv) as [[Heq _] | [_ H]]; [contradiction |].
    destruct (relax_le D _ u w y Hin Hy) as [r [Hr Hle]].
    destruct (oeq_sym_some _ _ _ H Hr) as [x [Hx Hxr]]. exists x. split; [exact Hx | lra].
  Qed.

  Corollary label_goal : exists x, D g = Some x /\ x == 0.
  Proof.
    destruct (eq_at g g_lt) as [[_ H] | [Hn _]]; [| contradiction].
    exact (oeq_some _ _ H).
  Qed.
End Exact.
