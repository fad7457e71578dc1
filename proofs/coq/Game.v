(** * The game: a finite digraph, walks that end at the first goal, a
    history-dependent Defender, N Attacker types, and the weak PBNE.

    This file only defines; the results are in [Tel.v] (walk reduction),
    [Defender.v] (the Defender's per-prefix decomposition) and [Pbne.v].

    - Nature draws the Attacker's type [t] (its true goal) from the prior.
    - The Attacker walks from [s0] along arcs; the game ends at the first goal
      node reached (either goal), where type [t] pays the terminal cost
      [dterm t g] (the distance from [g] to its own goal).
    - After each step [u -> v] the Defender, who sees the walk and its own past
      allocations but not the type, allocates the step's weight [w u v] to one
      goal, drawn from a distribution over the types; type [t] pays the weight
      when it lands on [t].
    - Two goals are the case [types = [T1; T2]] ([TwoGoal.v]).

    Histories are lists, most recent element first.  A Defender information
    set is a reversed walk prefix [v :: u :: h] (the step [u -> v] just seen,
    after the earlier nodes [h]) together with the Defender's own past
    allocations. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
From DPP Require Import Sums.
Open Scope Q_scope.

Section Game.
  (** ** The instance *)
  Variable T : Type.                        (* Attacker types = goals *)
  Variable Tdec : forall x y : T, {x = y} + {x <> y}.
  Variable types : list T.                  (* all types, each once *)

  Variable V : Type.
  Variable Vdec : forall x y : V, {x = y} + {x <> y}.
  Variable E : V -> V -> Prop.              (* arcs *)
  Variable w : V -> V -> Q.                 (* arc weights *)
  Variable isgoal : V -> bool.              (* the goal nodes *)
  Variable dterm : T -> V -> Q.             (* terminal cost of type t at goal g *)
  Variable s0 : V.                          (* the start *)
  Variable prior : T -> Q.                  (* the prior over types *)

  (** A probability distribution over the types. *)
  Definition dist (f : T -> Q) : Prop := (forall t, 0 <= f t) /\ sumL f types == 1.

  (** ** Walks.  [gwalk u l]: from [u], the nodes [l] follow arcs, every node
      left is not a goal, and the last node is a goal: the game ends at the
      first goal reached.  [pwalk] drops the last condition (a walk prefix). *)
  Fixpoint gwalk (u : V) (l : list V) : Prop :=
    match l with
    | [] => isgoal u = true
    | v :: l' => isgoal u = false /\ E u v /\ gwalk v l'
    end.

  Fixpoint pwalk (u : V) (l : list V) : Prop :=
    match l with
    | [] => True
    | v :: l' => isgoal u = false /\ E u v /\ pwalk v l'
    end.

  (** ** Defender strategies.  A behavioural Defender maps its own past
      allocations [al], the earlier nodes [h], the current node [u] and the
      node [v] just entered to a distribution over the goals. *)
  Definition dstrat := list T -> list V -> V -> V -> T -> Q.

  Definition admissible (sigma : dstrat) : Prop :=
    forall al h u v, dist (sigma al h u v).

  (** A Defender that looks at the walk only. *)
  Definition wstrat := list V -> V -> V -> T -> Q.
  Definition of_w (s : wstrat) : dstrat := fun _ => s.

  (** [J t s h u l]: what type [t] pays along the rest [l] of a walk, from
      node [u] after the earlier nodes [h], against a walk-history Defender. *)
  Fixpoint J (t : T) (s : wstrat) (h : list V) (u : V) (l : list V) : Q :=
    match l with
    | [] => dterm t u
    | v :: l' => w u v * s h u v t + J t s (u :: h) v l'
    end.

  (** Against a Defender that also looks at its own past allocations, the
      cost of a fixed walk is an expectation over those allocations: [D] is
      the distribution of the Defender's own history so far, a list of
      (probability, allocations). *)
  Definition odist := list (Q * list T).

  Definition sumD (D : odist) (f : list T -> Q) : Q :=
    sumL (fun ra => fst ra * f (snd ra)) D.

  Definition stepD (sigma : dstrat) (D : odist) (h : list V) (u v : V) : odist :=
    flat_map (fun ra => map (fun a => (fst ra * sigma (snd ra) h u v a, a :: snd ra)) types) D.

  Fixpoint Jd (t : T) (sigma : dstrat) (D : odist) (h : list V) (u : V) (l : list V) : Q :=
    match l with
    | [] => dterm t u
    | v :: l' => w u v * sumD D (fun al => sigma al h u v t)
                 + Jd t sigma (stepD sigma D h u v) (u :: h) v l'
    end.

  Definition D0 : odist := [(1, [])].

  (** ** Non-reacting Attacker strategies: finite mixtures of walks from [s0]
      (the profile's strategies, one per type). *)
  Definition mixture := list (Q * list V).

  Definition valid_mixture (g : mixture) : Prop :=
    sumL fst g == 1 /\ forall p l, In (p, l) g -> 0 <= p /\ gwalk s0 l.

  (** U_t(σ, γ_t): type [t]'s expected cost. *)
  Definition Umix (t : T) (sigma : dstrat) (g : mixture) : Q :=
    sumL (fun pl => fst pl * Jd t sigma D0 [] s0 (snd pl)) g.

  (** ** Reacting Attacker strategies: behavioural strategies that see the
      Defender's realised past allocations [al], the earlier nodes [h] and
      the current node [u], and return a distribution over next nodes. *)
  Definition ratt := list T -> list V -> V -> list (Q * V).

  Definition stage (t a : T) (x : Q) : Q := if Tdec a t then x else 0.

  (** [RU n]: type [t]'s expected cost accrued in the first [n] steps (plus
      the terminal cost of the walks that ended by then).  The expected cost
      of the strategy is the limit of this nondecreasing sequence. *)
  Fixpoint RU (t : T) (sigma : dstrat) (g : ratt) (n : nat)
           (al : list T) (h : list V) (u : V) : Q :=
    if isgoal u then dterm t u else
    match n with
    | O => 0
    | S n' =>
        sumL (fun pv => fst pv *
          sumL (fun a => sigma al h u (snd pv) a *
                  (stage t a (w u (snd pv)) + RU t sigma g n' (a :: al) (u :: h) (snd pv)))
               types) (g al h u)
    end.

  (** A reacting strategy is valid to depth [n] when it plays a distribution
      over arcs at every non-goal history it reaches. *)
  Fixpoint rvalid (sigma : dstrat) (g : ratt) (n : nat) (al : list T) (h : list V) (u : V) : Prop :=
    if isgoal u then True else
    match n with
    | O => True
    | S n' =>
        sumL fst (g al h u) == 1 /\
        forall p v, In (p, v) (g al h u) ->
          0 <= p /\ E u v /\ forall a, In a types -> rvalid sigma g n' (a :: al) (u :: h) v
    end.

  (** The law of the walk prefixes after [n] steps: (probability, nodes). *)
  Fixpoint RW (sigma : dstrat) (g : ratt) (n : nat) (al : list T) (h : list V) (u : V)
    : list (Q * list V) :=
    if isgoal u then [(1, [])] else
    match n with
    | O => [(1, [])]
    | S n' =>
        flat_map (fun pv =>
          flat_map (fun a =>
            map (fun ql => (fst pv * sigma al h u (snd pv) a * fst ql, snd pv :: snd ql))
                (RW sigma g n' (a :: al) (u :: h) (snd pv)))
            types) (g al h u)
    end.

  Definition ended (u : V) (l : list V) : bool := isgoal (last l u).

  (** The probability that the game has ended within [n] steps. *)
  Definition tmass (sigma : dstrat) (g : ratt) (n : nat) : Q :=
    sumL (fun ql => if ended s0 (snd ql) then fst ql else 0) (RW sigma g n [] [] s0).

  Definition valid_ratt (sigma : dstrat) (g : ratt) : Prop := forall n, rvalid sigma g n [] [] s0.

  (** Admissible: the game ends with probability 1. *)
  Definition terminates (sigma : dstrat) (g : ratt) : Prop :=
    forall eps, 0 < eps -> exists n, 1 - eps <= tmass sigma g n.

  (** "The expected cost of [g] is at least [x]": the limit of [RU n] is. *)
  Definition cost_ge (t : T) (sigma : dstrat) (g : ratt) (x : Q) : Prop :=
    forall eps, 0 < eps -> exists n, x - eps <= RU t sigma g n [] [] s0.

  (** ** Information sets, masses, beliefs. *)
  (** An information set [v :: u :: h] is a reversed walk prefix (a [list V]). *)

  Fixpoint steps (h : list V) (u : V) (l : list V) : list (list V) :=
    match l with
    | [] => []
    | v :: l' => (v :: u :: h) :: steps (u :: h) v l'
    end.

  Definition visits (q : list V) (l : list V) : Q :=
    if in_dec (list_eq_dec Vdec) q (steps [] s0 l) then 1 else 0.

  (** [reach q g]: the probability that the mixture [g] passes through [q]. *)
  Definition reach (q : list V) (g : mixture) : Q :=
    sumL (fun pl => fst pl * visits q (snd pl)) g.

  Variable gamma : T -> mixture.            (* the profile's Attacker *)

  (** The Bayes masses m_t(q) = b_t · P_t(q), their total, and "on path". *)
  Definition mass (t : T) (q : list V) : Q := prior t * reach q (gamma t).
  Definition Z (q : list V) : Q := sumL (fun t => mass t q) types.
  Definition on_path (q : list V) : Prop := 0 < Z q.

  (** The beliefs the kernel uses: Bayes where the total mass is positive,
      the prior elsewhere (off the path anything goes in a weak PBNE). *)
  Definition bayes (q : list V) (t : T) : Q :=
    if Qlt_le_dec 0 (Z q) then mass t q / Z q else prior t.

  (** ** The Defender's payoff and continuation payoffs. *)
  Definition Upay (sigma : dstrat) : Q := sumL (fun t => prior t * Umix t sigma (gamma t)) types.

  (** The rest of the walk after the information set [q], if the walk passes
      through it. *)
  Fixpoint after (q : list V) (h : list V) (u : V) (l : list V) : option (list V) :=
    match l with
    | [] => None
    | v :: l' => if list_eq_dec Vdec (v :: u :: h) q then Some l' else after q (u :: h) v l'
    end.

  (** What type [t] pays from the information set [(al, q)] on, along a walk
      through [q] (the current step's allocation included). *)
  Definition cont (t : T) (sigma : dstrat) (al : list T) (q : list V) (l : list V) : Q :=
    match q, after q [] s0 l with
    | v :: u :: h, Some r => Jd t sigma [(1, al)] h u (v :: r)
    | _, _ => 0
    end.

  (** Type [t]'s expected continuation cost given that it reached [q]. *)
  Definition condcost (t : T) (sigma : dstrat) (al : list T) (q : list V) : Q :=
    sumL (fun pl => fst pl * cont t sigma al q (snd pl)) (gamma t) / reach q (gamma t).

  (** The Defender's expected continuation payoff at [(al, q)] under belief [mu]. *)
  Definition CP (mu : list V -> T -> Q) (sigma : dstrat) (al : list T) (q : list V) : Q :=
    sumL (fun t => mu q t * condcost t sigma al q) types.

  (** ** The weak PBNE (the paper's Definition 1, for N types): the Attacker's
      best response (5b) over all admissible strategies, reacting ones
      included; the Defender's sequential rationality at every information set
      on the path (its own past allocations arbitrary), against every
      deviation; Bayes beliefs wherever Bayes' rule applies. *)
  Definition weak_pbne (sigma : dstrat) (mu : list V -> T -> Q) : Prop :=
    (forall t, In t types -> valid_mixture (gamma t)) /\
    admissible sigma /\
    (forall t, In t types -> forall g : ratt, valid_ratt sigma g -> terminates sigma g ->
       cost_ge t sigma g (Umix t sigma (gamma t))) /\
    (forall q, on_path q -> forall al sigma', admissible sigma' -> CP mu sigma' al q <= CP mu sigma al q) /\
    (forall q, on_path q -> forall t, In t types -> mu q t == mass t q / Z q).

  (** The Bayesian Nash condition (5a) for the Defender, at the root. *)
  Definition defender_optimal (sigma : dstrat) : Prop :=
    forall sigma', admissible sigma' -> Upay sigma' <= Upay sigma.
End Game.
