(** * What the kernel's checks give: a weak PBNE of the untruncated game.

    [pbne_of_checks]: for a Defender that looks at the walk only, if every
    type's mixture costs at most every walk (the Attacker check, which the
    kernel establishes with potentials, [Potential.v] / [Markov.v]) and the
    Defender is greedy on the Bayes masses at every on-path prefix (the
    Defender check), the profile with Bayes beliefs is a weak PBNE: TEL.4
    ([Tel.v]) lifts the Attacker check to every admissible strategy, reacting
    ones included, and L3.1/L3.3 ([Defender.v]) turn the greedy test into
    sequential rationality against every deviation. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel Defender.
Open Scope Q_scope.

Section Pbne.
  Variable T : Type.
  Variable Tdec : forall x y : T, {x = y} + {x <> y}.
  Variable types : list T.
  Hypothesis types_nodup : NoDup types.
  Variable V : Type.
  Variable Vdec : forall x y : V, {x = y} + {x <> y}.
  Variable E : V -> V -> Prop.
  Variable w : V -> V -> Q.
  Variable isgoal : V -> bool.
  Variable dterm : T -> V -> Q.
  Variable s0 : V.
  Variable prior : T -> Q.
  Hypothesis w_nonneg : forall u v, E u v -> 0 <= w u v.
  Hypothesis dterm_nonneg : forall t g, 0 <= dterm t g.
  Hypothesis prior_nonneg : forall t, 0 <= prior t.
  Variable gamma : T -> mixture V.

  Theorem pbne_of_checks : forall s : wstrat T V,
    (forall h u v, dist T types (s h u v)) ->
    (forall t, In t types -> valid_mixture V E isgoal s0 (gamma t)) ->
    (forall t, In t types -> forall l, gwalk V E isgoal s0 l ->
       Umix T types V w dterm s0 t (of_w T V s) (gamma t) <= J T V w dterm t s [] s0 l) ->
    (forall q, on_path T types V Vdec s0 prior gamma q -> greedy T types V Vdec s0 prior gamma s q) ->
    weak_pbne T Tdec types V Vdec E w isgoal dterm s0 prior gamma (of_w T V s)
              (bayes T types V Vdec s0 prior gamma).
  Proof.
    intros s Hs Hgam Hatt Hgreedy.
    split; [exact Hgam |]. split; [intros al h u v; apply Hs |]. split; [| split].
    - intros t Ht g Hv Hterm.
      apply (tel4 T Tdec types types_nodup V E w isgoal dterm s0 w_nonneg dterm_nonneg s Hs t Ht g);
        [exact (Hatt t Ht) | exact Hv | exact Hterm].
    - intros q Hon al sigma' Hadm.
      exact (greedy_seq_rational T types V Vdec E w isgoal dterm s0 prior w_nonneg prior_nonneg
               gamma Hgam s Hs Hgreedy q Hon al sigma' Hadm).
    - intros q Hon t _. unfold bayes. destruct (Qlt_le_dec 0 (Z T types V Vdec s0 prior gamma q)) as [_ | Hn];
        [reflexivity | unfold on_path in Hon; lra].
  Qed.

  (** The Bayesian Nash condition (5a) for the Defender follows as well. *)
  Theorem defender_optimal_of_checks : forall s : wstrat T V,
    (forall h u v, dist T types (s h u v)) ->
    (forall t, In t types -> valid_mixture V E isgoal s0 (gamma t)) ->
    (forall q, on_path T types V Vdec s0 prior gamma q -> greedy T types V Vdec s0 prior gamma s q) ->
    defender_optimal T types V w dterm s0 prior gamma (of_w T V s).
  Proof.
    intros s Hs Hgam Hg.
    exact (greedy_optimal T types V Vdec E w isgoal dterm s0 prior w_nonneg prior_nonneg gamma Hgam s Hs Hg).
  Qed.
End Pbne.
