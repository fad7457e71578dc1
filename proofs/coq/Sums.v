(** * Finite sums over lists, in [Q].

    Every expectation of the game is a finite sum: over a mixture's walks, over
    the goal types, over the prefixes of a walk trie.  This file holds the few
    facts about such sums the other files use (linearity, exchange, indicator
    sums, monotonicity), stated up to [Qeq]. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
Open Scope Q_scope.

Fixpoint sumL {A : Type} (f : A -> Q) (l : list A) : Q :=
  match l with
  | [] => 0
  | x :: l' => f x + sumL f l'
  end.

Section Sums.
  Context {A : Type}.

  Lemma sumL_nil (f : A -> Q) : sumL f [] == 0.
  Proof. reflexivity. Qed.

  Lemma sumL_app (f : A -> Q) l1 l2 : sumL f (l1 ++ l2) == sumL f l1 + sumL f l2.
  Proof. induction l1 as [| x l IH]; simpl; [ring | rewrite IH; ring]. Qed.

  Lemma sumL_ext (f g : A -> Q) l :
    (forall x, In x l -> f x == g x) -> sumL f l == sumL g l.
  Proof.
    induction l as [| x l IH]; intros H; simpl; [reflexivity |].
    rewrite (H x (or_introl eq_refl)), IH; [reflexivity |].
    intros y Hy; apply H; right; exact Hy.
  Qed.

  Lemma sumL_plus (f g : A -> Q) l : sumL (fun x => f x + g x) l == sumL f l + sumL g l.
  Proof. induction l as [| x l IH]; simpl; [ring | rewrite IH; ring]. Qed.

  Lemma sumL_minus (f g : A -> Q) l : sumL (fun x => f x - g x) l == sumL f l - sumL g l.
  Proof. induction l as [| x l IH]; simpl; [ring | rewrite IH; ring]. Qed.

  Lemma sumL_scale (c : Q) (f : A -> Q) l : sumL (fun x => c * f x) l == c * sumL f l.
  Proof. induction l as [| x l IH]; simpl; [ring | rewrite IH; ring]. Qed.

  Lemma sumL_scale_r (c : Q) (f : A -> Q) l : sumL (fun x => f x * c) l == sumL f l * c.
  Proof. induction l as [| x l IH]; simpl; [ring | rewrite IH; ring]. Qed.

  Lemma sumL_zero (f : A -> Q) l : (forall x, In x l -> f x == 0) -> sumL f l == 0.
  Proof.
    intros H. rewrite (sumL_ext f (fun _ => 0)); [| exact H]. clear H.
    induction l as [| x l IH]; simpl; [reflexivity | rewrite IH; ring].
  Qed.

  Lemma sumL_nonneg (f : A -> Q) l : (forall x, In x l -> 0 <= f x) -> 0 <= sumL f l.
  Proof.
    induction l as [| x l IH]; intros H; simpl; [lra |].
    pose proof (H x (or_introl eq_refl)).
    assert (0 <= sumL f l) by (apply IH; intros y Hy; apply H; right; exact Hy).
    lra.
  Qed.

  Lemma sumL_le (f g : A -> Q) l : (forall x, In x l -> f x <= g x) -> sumL f l <= sumL g l.
  Proof.
    induction l as [| x l IH]; intros H; simpl; [lra |].
    pose proof (H x (or_introl eq_refl)).
    assert (sumL f l <= sumL g l) by (apply IH; intros y Hy; apply H; right; exact Hy).
    lra.
  Qed.

  Lemma sumL_filter (f : A -> Q) (p : A -> bool) l :
    sumL f (filter p l) == sumL (fun x => if p x then f x else 0) l.
  Proof.
    induction l as [| x l IH]; simpl; [reflexivity |].
    destruct (p x); simpl; rewrite IH; ring.
  Qed.

  (** A nonnegative sum is zero only if every term is. *)
  Lemma sumL_nonneg_zero (f : A -> Q) l :
    (forall x, In x l -> 0 <= f x) -> sumL f l == 0 -> forall x, In x l -> f x == 0.
  Proof.
    induction l as [| y l IH]; intros H0 Hs x Hx; [destruct Hx |]. simpl in Hs.
    assert (Hy : 0 <= f y) by (apply H0; left; reflexivity).
    assert (Hl : 0 <= sumL f l) by (apply sumL_nonneg; intros z Hz; apply H0; right; exact Hz).
    destruct Hx as [<- | Hx]; [lra |].
    apply IH; [intros z Hz; apply H0; right; exact Hz | lra | exact Hx].
  Qed.

  (** A single term of a nonnegative sum is at most the sum. *)
  Lemma sumL_term_le (f : A -> Q) l x :
    (forall y, In y l -> 0 <= f y) -> In x l -> f x <= sumL f l.
  Proof.
    induction l as [| y l IH]; intros H0 Hx; [destruct Hx |]. simpl.
    assert (Hy : 0 <= f y) by (apply H0; left; reflexivity).
    assert (Hl : 0 <= sumL f l) by (apply sumL_nonneg; intros z Hz; apply H0; right; exact Hz).
    destruct Hx as [<- | Hx]; [lra |].
    assert (f x <= sumL f l) by (apply IH; [intros z Hz; apply H0; right; exact Hz | exact Hx]).
    lra.
  Qed.
End Sums.

Section Sums2.
  Context {A B : Type}.

  Lemma sumL_map (f : B -> Q) (g : A -> B) l : sumL f (map g l) == sumL (fun x => f (g x)) l.
  Proof. induction l as [| x l IH]; simpl; [reflexivity | rewrite IH; reflexivity]. Qed.

  Lemma sumL_flat_map (f : B -> Q) (g : A -> list B) l :
    sumL f (flat_map g l) == sumL (fun x => sumL f (g x)) l.
  Proof.
    induction l as [| x l IH]; simpl; [reflexivity |].
    rewrite sumL_app, IH. reflexivity.
  Qed.

  Lemma sumL_swap (f : A -> B -> Q) (la : list A) (lb : list B) :
    sumL (fun x => sumL (fun y => f x y) lb) la == sumL (fun y => sumL (fun x => f x y) la) lb.
  Proof.
    induction la as [| x la IH]; simpl.
    - rewrite sumL_zero; [reflexivity | intros; reflexivity].
    - rewrite IH, <- sumL_plus. reflexivity.
  Qed.

End Sums2.

(** Indicator sums: over a duplicate-free list containing [a], the sum of
    [f x] times "x is a" is [f a]. *)
Section Indicator.
  Context {A : Type} (Adec : forall x y : A, {x = y} + {x <> y}).

  Definition ind (a x : A) : Q := if Adec x a then 1 else 0.

  Lemma sumL_ind (f : A -> Q) (l : list A) (a : A) :
    NoDup l -> In a l -> sumL (fun x => f x * ind a x) l == f a.
  Proof.
    induction l as [| y l IH]; intros Hnd Hin; [destruct Hin |].
    inversion Hnd as [| y' l' Hny Hnd']; subst. simpl. unfold ind at 1.
    destruct (Adec y a) as [-> | Hne].
    - rewrite sumL_zero; [ring |].
      intros x Hx. unfold ind. destruct (Adec x a) as [-> | _]; [contradiction | ring].
    - destruct Hin as [-> | Hin]; [contradiction |].
      rewrite (IH Hnd' Hin). ring.
  Qed.

  Lemma sumL_ind_out (f : A -> Q) (l : list A) (a : A) :
    ~ In a l -> sumL (fun x => f x * ind a x) l == 0.
  Proof.
    intros Hn. apply sumL_zero. intros x Hx. unfold ind.
    destruct (Adec x a) as [-> | _]; [contradiction | ring].
  Qed.
End Indicator.

Lemma Qmul_le_l : forall c x y : Q, 0 <= c -> x <= y -> c * x <= c * y.
Proof.
  intros c x y Hc Hxy. rewrite (Qmult_comm c x), (Qmult_comm c y).
  apply Qmult_le_compat_r; assumption.
Qed.

Lemma last_cons : forall (A : Type) (l : list A) (v u : A), last (v :: l) u = last l v.
Proof.
  intros A. induction l as [| x l IH]; intros v u; [reflexivity |].
  change (last (x :: l) u = last (x :: l) v). rewrite !IH. reflexivity.
Qed.

Lemma map_nth_seq : forall (A : Type) (q : list A) d, map (fun t => nth t q d) (seq 0 (length q)) = q.
Proof.
  intros A. induction q as [| x q IH]; intros d; simpl; [reflexivity |]. f_equal.
  rewrite <- seq_shift, map_map. simpl. apply IH.
Qed.

