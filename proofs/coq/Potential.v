(** * Potential lower bounds for walks on a state graph.

    A walk of a state graph stops at the first goal state it reaches and then
    pays a terminal cost.  A potential that is feasible — at most the terminal
    cost at goal states, at most [cost + potential] along every arc from a
    non-goal state — on a set of states closed under the walks' arcs bounds
    the cost of every walk from below (the dual certificate of a shortest-path
    problem: the kernel checks it, it never computes it).  Nothing here needs
    finiteness or nonnegative costs. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
Open Scope Q_scope.

Section States.
  Variable S : Type.
  Variable arc : S -> S -> Prop.
  Variable cost : S -> S -> Q.
  Variable goal : S -> Prop.
  Variable term : S -> Q.               (* terminal cost at a goal state *)

  Fixpoint swalk (s : S) (l : list S) : Prop :=
    match l with
    | [] => goal s
    | y :: l' => ~ goal s /\ arc s y /\ swalk y l'
    end.

  Fixpoint scost (s : S) (l : list S) : Q :=
    match l with
    | [] => term s
    | y :: l' => cost s y + scost y l'
    end.

  Variable R : S -> Prop.
  Hypothesis R_closed : forall s y, R s -> ~ goal s -> arc s y -> R y.

  Definition feasible (phi : S -> Q) : Prop :=
    (forall s, R s -> goal s -> phi s <= term s) /\
    (forall s y, R s -> ~ goal s -> arc s y -> phi s <= cost s y + phi y).

  Theorem potential_bound :
    forall phi, feasible phi -> forall l s, R s -> swalk s l -> phi s <= scost s l.
  Proof.
    intros phi [Ht Ha]. induction l as [| y l IH]; intros s Hr Hw; simpl in *.
    - apply Ht; assumption.
    - destruct Hw as [Hng [Hsy Hw]].
      pose proof (IH y (R_closed s y Hr Hng Hsy) Hw).
      pose proof (Ha s y Hr Hng Hsy). lra.
  Qed.
End States.

(** ** Potentials with values in the rationals extended by +∞ ([None]):
    the kernel's labels may be +∞; a feasible extended potential is finite
    at every state from which a walk reaches a goal state, and bounds it. *)
Definition ole (a b : option Q) : Prop :=
  match a, b with
  | _, None => True
  | Some x, Some y => x <= y
  | None, Some _ => False
  end.

Definition oaddq (x : Q) (b : option Q) : option Q :=
  match b with Some y => Some (x + y) | None => None end.

Section Extended.
  Variable S : Type.
  Variable arc : S -> S -> Prop.
  Variable cost : S -> S -> Q.
  Variable goal : S -> Prop.
  Variable term : S -> Q.
  Variable R : S -> Prop.
  Hypothesis R_closed : forall s y, R s -> ~ goal s -> arc s y -> R y.

  Definition feasible_ext (phi : S -> option Q) : Prop :=
    (forall s, R s -> goal s -> ole (phi s) (Some (term s))) /\
    (forall s y, R s -> ~ goal s -> arc s y -> ole (phi s) (oaddq (cost s y) (phi y))).

  Theorem potential_bound_ext : forall phi, feasible_ext phi ->
    forall l s, R s -> swalk S arc goal s l -> exists x, phi s = Some x /\ x <= scost S cost term s l.
  Proof.
    intros phi [Ht Ha]. induction l as [| y l IH]; intros s Hr Hw; simpl in *.
    - specialize (Ht s Hr Hw). destruct (phi s) as [x |] eqn:Hx; simpl in Ht; [exists x; auto | destruct Ht].
    - destruct Hw as [Hng [Hsy Hw]].
      destruct (IH y (R_closed s y Hr Hng Hsy) Hw) as [z [Hz Hle]].
      specialize (Ha s y Hr Hng Hsy). rewrite Hz in Ha. simpl in Ha.
      destruct (phi s) as [x |] eqn:Hx; simpl in Ha; [| destruct Ha]. exists x. split; [reflexivity | lra].
  Qed.
End Extended.
