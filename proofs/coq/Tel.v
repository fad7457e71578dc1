(** * TEL.4, walk reduction: against a Defender that looks at the walk only,
    an Attacker that reacts to the Defender's realised allocations has an
    expected cost that is an average of walk costs, so a best response among
    walks is a best response among all admissible strategies.

    The expected cost of a reacting strategy is the limit of [RU n], the cost
    accrued in the first [n] steps (plus the terminal costs of the walks that
    ended by then).  [RU_decomp] writes [RU n] as an average, over the law
    [RW n] of the walk prefixes after [n] steps, of the walk costs [Jp]
    (the ended prefixes are walks of the game: [Jp = J]); [tel4] concludes
    that the limit is at least any lower bound on the walk costs, for every
    strategy that ends the game with probability 1. *)

From Coq Require Import QArith Lqa List.
Import ListNotations.
From DPP Require Import Sums Game.
Open Scope Q_scope.

Section Tel.
  Variable T : Type.
  Variable Tdec : forall x y : T, {x = y} + {x <> y}.
  Variable types : list T.
  Hypothesis types_nodup : NoDup types.
  Variable V : Type.
  Variable E : V -> V -> Prop.
  Variable w : V -> V -> Q.
  Variable isgoal : V -> bool.
  Variable dterm : T -> V -> Q.
  Variable s0 : V.
  Hypothesis w_nonneg : forall u v, E u v -> 0 <= w u v.
  Hypothesis dterm_nonneg : forall t g, 0 <= dterm t g.

  Notation dist := (dist T types).
  Notation gwalk := (gwalk V E isgoal).
  Notation pwalk := (pwalk V E isgoal).
  Notation J := (J T V w dterm).
  Notation RU := (RU T Tdec types V w isgoal dterm).
  Notation RW := (RW T types V isgoal).
  Notation rvalid := (rvalid T types V E isgoal).

  (** The cost of a walk prefix: the terminal cost only if it ended. *)
  Fixpoint Jp (t : T) (s : wstrat T V) (h : list V) (u : V) (l : list V) : Q :=
    match l with
    | [] => if isgoal u then dterm t u else 0
    | v :: l' => w u v * s h u v t + Jp t s (u :: h) v l'
    end.

  Lemma Jp_J : forall t s l h u, gwalk u l -> Jp t s h u l == J t s h u l.
  Proof.
    intros t s. induction l as [| v l IH]; intros h u Hw; simpl in *.
    - rewrite Hw. reflexivity.
    - destruct Hw as [_ [_ Hw]]. rewrite (IH (u :: h) v Hw). reflexivity.
  Qed.

  Lemma Jp_nonneg : forall t s, (forall h u v, dist (s h u v)) ->
    forall l h u, pwalk u l -> 0 <= Jp t s h u l.
  Proof.
    intros t s Hs. induction l as [| v l IH]; intros h u Hw; simpl in *.
    - destruct (isgoal u); [apply dterm_nonneg | lra].
    - destruct Hw as [_ [Huv Hw]].
      pose proof (IH (u :: h) v Hw). pose proof (w_nonneg u v Huv).
      destruct (Hs h u v) as [Hnn _]. pose proof (Hnn t).
      assert (0 <= w u v * s h u v t) by (apply Qmult_le_0_compat; assumption). lra.
  Qed.

  Lemma sum_stage : forall (f : T -> Q) t x, In t types ->
    sumL (fun a => f a * stage T Tdec t a x) types == f t * x.
  Proof.
    intros f t x Ht.
    rewrite (sumL_ext _ (fun a => (f a * x) * ind Tdec t a)).
    - apply (sumL_ind Tdec (fun a => f a * x)); [exact types_nodup | exact Ht].
    - intros a _. unfold stage, ind. destruct (Tdec a t); ring.
  Qed.

  Section Walker.
    Variable sigma : dstrat T V.
    Hypothesis adm : admissible T types V sigma.
    Variable g : ratt T V.

    Lemma RW_mass : forall n al h u, rvalid sigma g n al h u ->
      sumL fst (RW sigma g n al h u) == 1.
    Proof.
      induction n as [| n IH]; intros al h u Hv; simpl in *;
        destruct (isgoal u) eqn:Hg; simpl; try ring.
      destruct Hv as [Hm Hall].
      rewrite sumL_flat_map, <- Hm. apply sumL_ext. intros [p v] Hin. simpl.
      destruct (Hall p v Hin) as [_ [_ Hnext]].
      rewrite sumL_flat_map.
      rewrite (sumL_ext _ (fun a => p * sigma al h u v a)).
      - rewrite sumL_scale. destruct (adm al h u v) as [_ H1]. rewrite H1. ring.
      - intros a Ha. rewrite sumL_map. simpl.
        rewrite sumL_scale, (IH (a :: al) (u :: h) v (Hnext a Ha)). ring.
    Qed.

    Lemma RW_shape : forall n al h u q l, rvalid sigma g n al h u ->
      In (q, l) (RW sigma g n al h u) ->
      0 <= q /\ pwalk u l /\ (ended V isgoal u l = true -> gwalk u l).
    Proof.
      induction n as [| n IH]; intros al h u q l Hv Hin; simpl in *;
        destruct (isgoal u) eqn:Hg.
      1, 2, 3: destruct Hin as [Heq | []]; inversion Heq; subst;
        repeat split; try lra; unfold ended; simpl; congruence.
      destruct Hv as [_ Hall].
      apply in_flat_map in Hin as [[p v] [Hpv Hin]].
      apply in_flat_map in Hin as [a [Ha Hin]].
      apply in_map_iff in Hin as [[q' l'] [Heq Hin]]. simpl in Heq.
      inversion Heq; subst q l. clear Heq.
      destruct (Hall p v Hpv) as [Hp [Huv Hnext]].
      destruct (IH _ _ _ _ _ (Hnext a Ha) Hin) as [Hq [Hw He]].
      destruct (adm al h u v) as [Hs _].
      split; [| split].
      - apply Qmult_le_0_compat; [apply Qmult_le_0_compat |]; auto.
      - simpl. auto.
      - unfold ended. intros Hend. simpl. split; [exact Hg | split; [exact Huv |]].
        apply He. unfold ended in *. rewrite last_cons in Hend. exact Hend.
    Qed.
  End Walker.

  (** ** The decomposition (TEL.4, first half). *)
  Section Decomp.
    Variable s : wstrat T V.
    Hypothesis sdist : forall h u v, dist (s h u v).
    Let sigma := of_w T V s.
    Lemma adm : admissible T types V sigma.
    Proof. intros al h u v. apply sdist. Qed.
    Variable t : T.
    Hypothesis t_in : In t types.
    Variable g : ratt T V.

    Theorem RU_decomp : forall n al h u, rvalid sigma g n al h u ->
      RU t sigma g n al h u == sumL (fun ql => fst ql * Jp t s h u (snd ql)) (RW sigma g n al h u).
    Proof.
      induction n as [| n IH]; intros al h u Hv; simpl in *;
        destruct (isgoal u) eqn:Hg; simpl; try (rewrite Hg; ring).
      destruct Hv as [_ Hall].
      rewrite sumL_flat_map. apply sumL_ext. intros [p v] Hin. simpl.
      destruct (Hall p v Hin) as [_ [_ Hnext]].
      rewrite sumL_flat_map.
      transitivity (sumL (fun a => p * s h u v a *
                      (w u v * s h u v t + RU t sigma g n (a :: al) (u :: h) v)) types).
      - rewrite <- sumL_scale.
        rewrite (sumL_ext _ (fun a => p * (s h u v a * stage T Tdec t a (w u v))
                                      + p * (s h u v a * RU t sigma g n (a :: al) (u :: h) v))).
        2: { intros a _. unfold sigma, of_w. ring. }
        rewrite sumL_plus, !sumL_scale, (sum_stage _ _ _ t_in).
        rewrite (sumL_ext (fun a => p * s h u v a * _)
                  (fun a => (p * (w u v * s h u v t)) * s h u v a
                            + p * (s h u v a * RU t sigma g n (a :: al) (u :: h) v))).
        2: { intros a _. simpl. ring. }
        rewrite sumL_plus, sumL_scale, sumL_scale.
        destruct (sdist h u v) as [_ H1]. rewrite H1. ring.
      - apply sumL_ext. intros a Ha. rewrite sumL_map. simpl.
        rewrite (IH (a :: al) (u :: h) v (Hnext a Ha)).
        change (sigma al h u v a) with (s h u v a).
        rewrite (sumL_ext (fun ql => p * s h u v a * fst ql * (w u v * s h u v t + Jp t s (u :: h) v (snd ql)))
                          (fun ql => (p * s h u v a * (w u v * s h u v t)) * fst ql
                                       + (p * s h u v a) * (fst ql * Jp t s (u :: h) v (snd ql)))).
        2: { intros ql _. simpl. ring. }
        rewrite sumL_plus, !sumL_scale.
        rewrite (RW_mass sigma adm g n (a :: al) (u :: h) v (Hnext a Ha)). ring.
    Qed.

    Lemma RU_nonneg : forall n al h u, rvalid sigma g n al h u -> 0 <= RU t sigma g n al h u.
    Proof.
      intros n al h u Hv. rewrite (RU_decomp n al h u Hv).
      apply sumL_nonneg. intros [q l] Hin. simpl.
      destruct (RW_shape sigma adm g n al h u q l Hv Hin) as [Hq [Hw _]].
      apply Qmult_le_0_compat; [exact Hq | exact (Jp_nonneg t s sdist l h u Hw)].
    Qed.

    (** Every walk costs at least [x], so after [n] steps the expected cost is
        at least [x] times the probability that the game has ended. *)
    Lemma RU_ge_ended : forall x n, (forall l, gwalk s0 l -> x <= J t s [] s0 l) ->
      rvalid sigma g n [] [] s0 -> x * tmass T types V isgoal s0 sigma g n <= RU t sigma g n [] [] s0.
    Proof.
      intros x n Hx Hv. rewrite (RU_decomp n [] [] s0 Hv). unfold tmass.
      rewrite <- sumL_scale. apply sumL_le. intros [q l] Hin. simpl.
      destruct (RW_shape sigma adm g n [] [] s0 q l Hv Hin) as [Hq [Hw He]].
      destruct (ended V isgoal s0 l) eqn:Hend.
      - rewrite (Jp_J t s l [] s0 (He eq_refl)).
        rewrite (Qmult_comm x q). apply Qmul_le_l; [exact Hq | exact (Hx l (He eq_refl))].
      - setoid_replace (x * 0) with 0 by ring.
        apply Qmult_le_0_compat; [exact Hq | exact (Jp_nonneg t s sdist l [] s0 Hw)].
    Qed.

    (** ** TEL.4: a lower bound on every walk's cost bounds the expected cost
        of every admissible strategy, reacting or not. *)
    Theorem tel4 : forall x, (forall l, gwalk s0 l -> x <= J t s [] s0 l) ->
      valid_ratt T types V E isgoal s0 sigma g -> terminates T types V isgoal s0 sigma g ->
      cost_ge T Tdec types V w isgoal dterm s0 t sigma g x.
    Proof.
      intros x Hx Hv Hterm eps Heps.
      destruct (Qlt_le_dec 0 x) as [Hpos | Hneg].
      - assert (Hex : 0 < eps / x) by (apply Qlt_shift_div_l; lra).
        destruct (Hterm (eps / x) Hex) as [n Hn]. exists n.
        pose proof (RU_ge_ended x n Hx (Hv n)) as H.
        assert (Hm : x * (1 - eps / x) <= x * tmass T types V isgoal s0 sigma g n)
          by (apply Qmul_le_l; lra).
        setoid_replace (x * (1 - eps / x)) with (x - eps) in Hm by (field; lra). lra.
      - exists O. pose proof (RU_nonneg O [] [] s0 (Hv O)). lra.
    Qed.
  End Decomp.

  (** ** Against a walk-history Defender, the own-history machinery is
      harmless: [Jd] of [of_w s] is [J] whatever the (normalised) law [D]
      of the Defender's own past. *)
  Lemma stepD_mass : forall sigma D h u v, admissible T types V sigma ->
    sumL fst (stepD T types V sigma D h u v) == sumL fst D.
  Proof.
    intros sigma D h u v Hadm. unfold stepD.
    rewrite sumL_flat_map. apply sumL_ext. intros [r al] _. rewrite sumL_map. simpl.
    rewrite sumL_scale. destruct (Hadm al h u v) as [_ H1]. rewrite H1. ring.
  Qed.

  Lemma sumD_const : forall D c, sumD T D (fun _ => c) == sumL fst D * c.
  Proof. intros D c. unfold sumD. apply sumL_scale_r. Qed.

  Lemma Jd_of_w : forall t s, (forall h u v, dist (s h u v)) ->
    forall l D h u, sumL fst D == 1 ->
    Jd T types V w dterm t (of_w T V s) D h u l == J t s h u l.
  Proof.
    intros t s Hs. induction l as [| v l IH]; intros D h u HD; simpl; [reflexivity |].
    unfold of_w at 1. rewrite sumD_const, HD.
    rewrite IH; [ring |]. rewrite stepD_mass; [exact HD |]. intros al h' u' v'. apply Hs.
  Qed.

  Lemma Umix_of_w : forall t s g, (forall h u v, dist (s h u v)) ->
    Umix T types V w dterm s0 t (of_w T V s) g == sumL (fun pl => fst pl * J t s [] s0 (snd pl)) g.
  Proof.
    intros t s g Hs. unfold Umix. apply sumL_ext. intros [p l] _. simpl.
    rewrite Jd_of_w; [reflexivity | exact Hs | unfold D0; simpl; ring].
  Qed.
End Tel.
