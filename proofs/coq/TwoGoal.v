(** * The two-goal game: the instance of [Game.v] with the types [T1], [T2].

    The paper's game has two goals: the Defender's action at each step is one
    probability [a] on the primary goal g1 (and 1 − a on g2).  [two_goal] is
    that Defender as a strategy of [Game.v]; [weak_pbne2] is the weak PBNE of
    the two-goal game, literally [Game.weak_pbne] with two types. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
From DPP Require Import Sums Game.
Open Scope Q_scope.

Inductive type2 := T1 | T2.

Definition type2_dec : forall x y : type2, {x = y} + {x <> y}.
Proof. decide equality. Defined.

Definition types2 : list type2 := [T1; T2].

Lemma types2_nodup : NoDup types2.
Proof. constructor; [intros [H | []]; discriminate | constructor; [intros [] | constructor]]. Qed.

Lemma types2_all : forall t, In t types2.
Proof. intros [|]; simpl; auto. Qed.

Section TwoGoal.
  Variable V : Type.
  Variable Vdec : forall x y : V, {x = y} + {x <> y}.
  Variable E : V -> V -> Prop.
  Variable w : V -> V -> Q.
  Variable isgoal : V -> bool.              (* g1 or g2 *)
  Variable dterm : type2 -> V -> Q.         (* d(g, g^θ) at a goal g *)
  Variable s0 : V.
  Variable b1 : Q.                          (* the prior of the primary type *)

  Definition prior2 (t : type2) : Q := match t with T1 => b1 | T2 => 1 - b1 end.

  (** A two-goal Defender: the probability it puts on g1 after each prefix. *)
  Definition two_goal (a : list V -> V -> V -> Q) : dstrat type2 V :=
    fun _ h u v t => match t with T1 => a h u v | T2 => 1 - a h u v end.

  Lemma two_goal_admissible : forall a, (forall h u v, 0 <= a h u v <= 1) ->
    admissible type2 types2 V (two_goal a).
  Proof.
    intros a Ha al h u v. specialize (Ha h u v). split.
    - intros [|]; simpl; lra.
    - simpl. ring.
  Qed.

  (** The weak PBNE of the two-goal game. *)
  Definition weak_pbne2 (gamma : type2 -> mixture V) (sigma : dstrat type2 V)
             (mu : list V -> type2 -> Q) : Prop :=
    weak_pbne type2 type2_dec types2 V Vdec E w isgoal dterm s0 prior2 gamma sigma mu.
End TwoGoal.
