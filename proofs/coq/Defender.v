(** * L3.1, the Defender's side: against a non-reacting Attacker the
    Defender's payoff decomposes over the prefixes of the walk trie, so a
    Defender greedy on the Bayes masses at each on-path prefix is optimal
    ((5a) of the paper) and sequentially rational with Bayes beliefs.

    Deviations range over every behavioural Defender, including those that
    look at their own past allocations: the law [Dat] of those allocations
    given the prefix does not depend on the type ([Jd_decomp]), so each
    prefix's allocation enters the payoff only through its average [sbar]
    (proofs/L3.md, L3.1). *)

From Coq Require Import QArith Lqa List Arith Lia.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel.
Open Scope Q_scope.

Section Defender.
  Variable T : Type.
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
  Hypothesis prior_nonneg : forall t, 0 <= prior t.
  Variable gamma : T -> mixture V.
  Hypothesis gamma_valid : forall t, In t types -> valid_mixture V E isgoal s0 (gamma t).

  Notation ldec := (ldec V Vdec).
  Notation dist := (dist T types).
  Notation steps := (steps V).
  Notation Jd := (Jd T types V w dterm).
  Notation mass := (mass T V Vdec s0 prior gamma).
  Notation Z := (Z T types V Vdec s0 prior gamma).
  Notation reach := (reach V Vdec s0).
  Notation visits := (visits V Vdec s0).

  (** ** The law of the Defender's own past allocations at a later prefix. *)
  Fixpoint Dat (sigma : dstrat T V) (D : odist T) (base pr : list V) : odist T :=
    if ldec pr base then D else
    match pr with
    | [] => []
    | x :: r => match r with
                | [] => []
                | y :: h => stepD T types V sigma (Dat sigma D base r) h y x
                end
    end.

  Lemma Dat_cons : forall sigma D base x y h,
    Dat sigma D base (x :: y :: h) =
    if ldec (x :: y :: h) base then D else stepD T types V sigma (Dat sigma D base (y :: h)) h y x.
  Proof. reflexivity. Qed.

  Lemma Dat_base : forall sigma D base, Dat sigma D base base = D.
  Proof.
    intros sigma D [| x [| y h]]; cbn [Dat];
      destruct (ldec _ _) as [_ | Hn]; try reflexivity; contradiction.
  Qed.

  Lemma Dat_shift : forall sigma D h u v k,
    Dat sigma D (u :: h) (k ++ v :: u :: h) =
    Dat sigma (stepD T types V sigma D h u v) (v :: u :: h) (k ++ v :: u :: h).
  Proof.
    intros sigma D h u v. induction k as [| x k IH].
    - cbn [app]. rewrite Dat_cons, Dat_base, Dat_base.
      destruct (ldec (v :: u :: h) (u :: h)) as [Heq | _]; [| reflexivity].
      apply (f_equal (@length V)) in Heq. simpl in Heq. lia.
    - cbn [app]. destruct (k ++ v :: u :: h) as [| y h'] eqn:Hk.
      + destruct k; discriminate.
      + rewrite !Dat_cons, IH.
        destruct (ldec (x :: y :: h') (u :: h)) as [Heq | _].
        { apply (f_equal (@length V)) in Heq, Hk. simpl in *. rewrite app_length in Hk. simpl in Hk. lia. }
        destruct (ldec (x :: y :: h') (v :: u :: h)) as [Heq | _]; [| reflexivity].
        apply (f_equal (@length V)) in Heq, Hk. simpl in *. rewrite app_length in Hk. simpl in Hk. lia.
  Qed.

  Definition sig_at (sigma : dstrat T V) (al : list T) (q : list V) (t : T) : Q :=
    match q with v :: u :: h => sigma al h u v t | _ => 0 end.
  Definition w_at (q : list V) : Q := match q with v :: u :: _ => w u v | _ => 0 end.

  (** The average allocation at [q]: over the law of the Defender's own past. *)
  Definition sbar (sigma : dstrat T V) (D : odist T) (base q : list V) (t : T) : Q :=
    sumD T (Dat sigma D base (tl q)) (fun al => sig_at sigma al q t).

  (** ** The decomposition of a walk's cost over its steps. *)
  Theorem Jd_decomp : forall t sigma l D h u,
    Jd t sigma D h u l ==
    sumL (fun q => w_at q * sbar sigma D (u :: h) q t) (steps h u l) + dterm t (last l u).
  Proof.
    intros t sigma. induction l as [| v l IH]; intros D h u; [simpl; ring |].
    cbn [Jd steps sumL]. rewrite IH, last_cons.
    replace (sbar sigma D (u :: h) (v :: u :: h) t) with (sumD T D (fun al => sigma al h u v t))
      by (unfold sbar; cbn [tl sig_at]; rewrite Dat_base; reflexivity). cbn [w_at].
    rewrite (sumL_ext (fun q => w_at q * sbar sigma (stepD T types V sigma D h u v) (v :: u :: h) q t)
                      (fun q => w_at q * sbar sigma D (u :: h) q t)); [ring |].
    intros q Hq. destruct (steps_shape V l (u :: h) v q Hq) as [v' [k ->]].
    unfold sbar. cbn [tl]. rewrite Dat_shift. reflexivity.
  Qed.

  (** ** Laws of own histories stay distributions. *)
  Definition odist_ok (D : odist T) : Prop :=
    sumL fst D == 1 /\ forall ra, In ra D -> 0 <= fst ra.

  Lemma stepD_ok : forall sigma D h u v, admissible T types V sigma -> odist_ok D ->
    odist_ok (stepD T types V sigma D h u v).
  Proof.
    intros sigma D h u v Hadm [Hm Hn]. split.
    - rewrite stepD_mass; assumption.
    - intros ra Hin. unfold stepD in Hin. apply in_flat_map in Hin as [[r al] [Hra Hin]].
      apply in_map_iff in Hin as [a [<- _]]. simpl.
      apply Qmult_le_0_compat; [exact (Hn _ Hra) | apply (Hadm al h u v)].
  Qed.

  Lemma Dat_ok : forall sigma D base, admissible T types V sigma -> base <> [] -> odist_ok D ->
    forall k, odist_ok (Dat sigma D base (k ++ base)).
  Proof.
    intros sigma D base Hadm Hb HD. induction k as [| x k IH]; [cbn [app]; rewrite Dat_base; exact HD |].
    cbn [app]. destruct (k ++ base) as [| y h] eqn:Hk.
    - destruct k; destruct base; try discriminate. contradiction.
    - rewrite Dat_cons. destruct (ldec (x :: y :: h) base); [exact HD |].
      apply stepD_ok; assumption.
  Qed.

  Lemma sbar_dist : forall sigma D base v u h, admissible T types V sigma ->
    odist_ok (Dat sigma D base (u :: h)) -> dist (sbar sigma D base (v :: u :: h)).
  Proof.
    intros sigma D base v u h Hadm [Hm Hn]. unfold sbar, sumD. cbn [tl sig_at]. split.
    - intros t. apply sumL_nonneg. intros [r al] Hin. simpl.
      apply Qmult_le_0_compat; [exact (Hn _ Hin) | apply (Hadm al h u v)].
    - rewrite sumL_swap. rewrite <- Hm. apply sumL_ext. intros [r al] _. simpl.
      rewrite sumL_scale. destruct (Hadm al h u v) as [_ H1]. rewrite H1. ring.
  Qed.

  Lemma sbar_of_w : forall s D base q t, odist_ok (Dat (of_w T V s) D base (tl q)) ->
    sbar (of_w T V s) D base q t == sig_at (of_w T V s) [] q t.
  Proof.
    intros s D base q t [Hm _]. unfold sbar.
    transitivity (sumD T (Dat (of_w T V s) D base (tl q)) (fun _ => sig_at (of_w T V s) [] q t)).
    - unfold sumD. apply sumL_ext. intros ra _. destruct q as [| v [| u h]]; reflexivity.
    - rewrite sumD_const, Hm. ring.
  Qed.

  (** ** Sums over the walk trie. *)
  Lemma trie_sum : forall (F : list V -> Q) (g : mixture V) (P : list (list V)),
    NoDup P -> (forall p l q, In (p, l) g -> In q (steps [] s0 l) -> In q P) ->
    sumL (fun pl => fst pl * sumL F (steps [] s0 (snd pl))) g == sumL (fun q => F q * reach q g) P.
  Proof.
    intros F g P HP Hinc. unfold reach.
    rewrite (sumL_ext _ (fun pl => sumL (fun q => fst pl * (F q * visits q (snd pl))) P)).
    - rewrite sumL_swap. apply sumL_ext. intros q _. rewrite <- sumL_scale.
      apply sumL_ext. intros pl _. ring.
    - intros [p l] Hin. simpl. rewrite sumL_scale.
      rewrite (sum_incl V Vdec F (steps [] s0 l) P (steps_nodup V l [] s0) HP).
      + reflexivity.
      + intros q Hq. exact (Hinc p l q Hin Hq).
  Qed.

  (** The trie: every information set some profile walk passes through. *)
  Definition trie : list (list V) :=
    nodup ldec (flat_map (fun t => flat_map (fun pl => steps [] s0 (snd pl)) (gamma t)) types).

  Lemma trie_nodup : NoDup trie.
  Proof. apply NoDup_nodup. Qed.

  Lemma trie_complete : forall t p l q, In t types -> In (p, l) (gamma t) ->
    In q (steps [] s0 l) -> In q trie.
  Proof.
    intros t p l q Ht Hpl Hq. unfold trie. apply nodup_In.
    apply in_flat_map. exists t. split; [exact Ht |].
    apply in_flat_map. exists (p, l). split; assumption.
  Qed.

  Lemma trie_arc : forall q, In q trie -> exists v u h, q = v :: u :: h /\ E u v.
  Proof.
    intros q Hq. unfold trie in Hq. apply nodup_In, in_flat_map in Hq as [t [Ht Hq]].
    apply in_flat_map in Hq as [[p l] [Hpl Hq]].
    destruct (gamma_valid t Ht) as [_ Hall]. destruct (Hall p l Hpl) as [_ Hw].
    exact (steps_pwalk V E isgoal l [] s0 q (gwalk_pwalk V E isgoal l s0 Hw) Hq).
  Qed.

  Lemma reach_nonneg : forall t q, In t types -> 0 <= reach q (gamma t).
  Proof.
    intros t q Ht. unfold reach. apply sumL_nonneg. intros [p l] Hin. simpl.
    destruct (gamma_valid t Ht) as [_ Hall]. destruct (Hall p l Hin) as [Hp _].
    unfold visits. destruct (in_dec _ _ _); [lra | lra].
  Qed.

  Lemma mass_nonneg : forall t q, In t types -> 0 <= mass t q.
  Proof.
    intros t q Ht. unfold Game.mass. apply Qmult_le_0_compat; [apply prior_nonneg | apply reach_nonneg; exact Ht].
  Qed.

  (** ** The greedy test on masses (no division), and why it is optimal. *)
  Definition greedy (s : wstrat T V) (q : list V) : Prop :=
    forall t t', In t types -> In t' types -> 0 < sig_at (of_w T V s) [] q t -> mass t' q <= mass t q.

  Lemma dist_pos : forall (f : T -> Q) l, (forall x, 0 <= f x) -> sumL f l == 1 ->
    exists x, In x l /\ 0 < f x.
  Proof.
    intros f l Hn. induction l as [| x l IH]; simpl; intros H1; [discriminate |].
    destruct (Qlt_le_dec 0 (f x)) as [Hp | Hz].
    - exists x. auto.
    - assert (Hl : sumL f l == 1) by (pose proof (Hn x); lra).
      destruct (IH Hl) as [y [Hy Hp]]. exists y. auto.
  Qed.

  Lemma greedy_best : forall s q (a : T -> Q), (forall h u v, dist (s h u v)) ->
    (exists v u h, q = v :: u :: h) -> greedy s q -> dist a ->
    sumL (fun t => a t * mass t q) types <= sumL (fun t => sig_at (of_w T V s) [] q t * mass t q) types.
  Proof.
    intros s q a Hs [v [u [h ->]]] Hg [Ha0 Ha1].
    cbn [sig_at of_w] in *. destruct (Hs h u v) as [Hs0 Hs1].
    destruct (dist_pos (s h u v) types Hs0 Hs1) as [ts [Hts Hpos]].
    set (M := mass ts (v :: u :: h)).
    assert (Hmax : forall t, In t types -> mass t (v :: u :: h) <= M)
      by (intros t Ht; apply (Hg ts t Hts Ht Hpos)).
    assert (HL : sumL (fun t => a t * mass t (v :: u :: h)) types <= sumL (fun t => a t * M) types).
    { apply sumL_le. intros t Ht. apply Qmul_le_l; [apply Ha0 | apply Hmax; exact Ht]. }
    assert (HR : sumL (fun t => s h u v t * mass t (v :: u :: h)) types == sumL (fun t => s h u v t * M) types).
    { apply sumL_ext. intros t Ht. destruct (Qlt_le_dec 0 (s h u v t)) as [Hp | Hz].
      - assert (mass ts (v :: u :: h) <= mass t (v :: u :: h)) by exact (Hg t ts Ht Hts Hp).
        pose proof (Hmax t Ht). assert (Heq : mass t (v :: u :: h) == M) by (unfold M in *; lra).
        rewrite Heq. reflexivity.
      - setoid_replace (s h u v t) with 0 by (pose proof (Hs0 t); lra). ring. }
    rewrite HR. rewrite sumL_scale_r in HL |- *. rewrite Ha1 in HL. rewrite Hs1. exact HL.
  Qed.

  (** Off the path every mass is zero. *)
  Lemma off_path_zero : forall q t, In t types -> Z q <= 0 -> mass t q == 0.
  Proof.
    intros q t Ht Hz. unfold Game.Z in Hz.
    assert (H0 : 0 <= Z q) by (apply sumL_nonneg; intros x Hx; apply mass_nonneg; exact Hx).
    unfold Game.Z in H0.
    apply (sumL_nonneg_zero (fun t => mass t q) types); [| lra | exact Ht].
    intros x Hx. apply mass_nonneg. exact Hx.
  Qed.

  (** The per-prefix comparison used at the root and at every information set. *)
  Lemma prefix_le : forall s sigma' D base q,
    (forall h u v, dist (s h u v)) -> admissible T types V sigma' ->
    (exists v u h, q = v :: u :: h /\ E u v) -> (on_path T types V Vdec s0 prior gamma q -> greedy s q) ->
    odist_ok (Dat sigma' D base (tl q)) -> odist_ok (Dat (of_w T V s) D base (tl q)) ->
    w_at q * sumL (fun t => sbar sigma' D base q t * mass t q) types <=
    w_at q * sumL (fun t => sbar (of_w T V s) D base q t * mass t q) types.
  Proof.
    intros s sigma' D base q Hs Hadm [v [u [h [-> Huv]]]] Hg Hok' Hok.
    apply Qmul_le_l; [cbn [w_at]; apply w_nonneg; exact Huv |].
    rewrite (sumL_ext (fun t => sbar (of_w T V s) D base (v :: u :: h) t * mass t (v :: u :: h))
                      (fun t => sig_at (of_w T V s) [] (v :: u :: h) t * mass t (v :: u :: h)))
      by (intros t _; rewrite sbar_of_w; [reflexivity | exact Hok]).
    destruct (Qlt_le_dec 0 (Z (v :: u :: h))) as [Hon | Hoff].
    - apply (greedy_best s (v :: u :: h)); [exact Hs | eauto | apply Hg; exact Hon |].
      apply sbar_dist; [exact Hadm | exact Hok'].
    - rewrite !(sumL_zero (fun t => _ * mass t (v :: u :: h))); [lra | |];
        intros t Ht; rewrite (off_path_zero _ t Ht Hoff); ring.
  Qed.

  (** ** L3.1 at the root: the decomposition of the Defender's payoff. *)
  Definition term_all : Q :=
    sumL (fun t => prior t * sumL (fun pl => fst pl * dterm t (last (snd pl) s0)) (gamma t)) types.

  Theorem Upay_decomp : forall sigma,
    Upay T types V w dterm s0 prior gamma sigma ==
    sumL (fun q => w_at q * sumL (fun t => sbar sigma (D0 T) [s0] q t * mass t q) types) trie + term_all.
  Proof.
    intros sigma. unfold Upay, Umix, term_all.
    rewrite (sumL_ext (fun q => w_at q * sumL (fun t => sbar sigma (D0 T) [s0] q t * mass t q) types)
                      (fun q => sumL (fun t => prior t * ((w_at q * sbar sigma (D0 T) [s0] q t) * reach q (gamma t))) types))
      by (intros q _; rewrite <- sumL_scale; apply sumL_ext; intros t _; unfold Game.mass; ring).
    rewrite <- sumL_swap, <- sumL_plus. apply sumL_ext. intros t Ht.
    rewrite sumL_scale.
    rewrite <- (trie_sum (fun q => w_at q * sbar sigma (D0 T) [s0] q t) (gamma t) trie trie_nodup)
      by (intros p l q Hpl Hq; exact (trie_complete t p l q Ht Hpl Hq)).
    enough (H : sumL (fun pl => fst pl * Jd t sigma (D0 T) [] s0 (snd pl)) (gamma t) ==
                sumL (fun pl => fst pl * sumL (fun q => w_at q * sbar sigma (D0 T) [s0] q t) (steps [] s0 (snd pl))
                                + fst pl * dterm t (last (snd pl) s0)) (gamma t))
      by (rewrite H, sumL_plus; ring).
    apply sumL_ext. intros [p l] _. simpl. rewrite Jd_decomp. ring.
  Qed.

  (** (5a): greedy on the masses at every on-path prefix ⇒ optimal. *)
  Theorem greedy_optimal : forall s, (forall h u v, dist (s h u v)) ->
    (forall q, on_path T types V Vdec s0 prior gamma q -> greedy s q) ->
    defender_optimal T types V w dterm s0 prior gamma (of_w T V s).
  Proof.
    intros s Hs Hg sigma' Hadm. rewrite !Upay_decomp.
    assert (Hadm_s : admissible T types V (of_w T V s)) by (intros al h u v; apply Hs).
    apply Qplus_le_compat; [| apply Qle_refl].
    apply sumL_le. intros q Hq. destruct (trie_arc q Hq) as [v [u [h [-> Huv]]]].
    assert (Hok : forall sg, admissible T types V sg -> odist_ok (Dat sg (D0 T) [s0] (tl (v :: u :: h)))).
    { intros sg Hsg. pose proof (trie_arc _ Hq) as _.
      unfold trie in Hq. apply nodup_In, in_flat_map in Hq as [t [_ Hq]].
      apply in_flat_map in Hq as [[p l] [_ Hq]].
      destruct (steps_shape V l [] s0 _ Hq) as [v' [k Hk]]. inversion Hk; subst.
      cbn [tl]. rewrite H1. apply Dat_ok; [exact Hsg | discriminate | unfold odist_ok, D0; simpl; split; [ring | intros ra [<- | []]; simpl; lra]]. }
    apply prefix_le; eauto.
  Qed.

  (** ** L3.3: sequential rationality at every information set on the path. *)
  Notation cont := (cont T types V Vdec w dterm s0).
  Notation extb := (extb V Vdec).

  Lemma extb_steps : forall v u h r q, In q (steps h u (v :: r)) -> extb (v :: u :: h) q = true.
  Proof.
    intros v u h r q Hq. apply extb_spec. destruct Hq as [<- | Hq].
    - exists []. reflexivity.
    - destruct (steps_shape V r (u :: h) v q Hq) as [v' [k ->]]. exists (v' :: k). reflexivity.
  Qed.

  Lemma cont_eq : forall t sigma al v u h l,
    cont t sigma al (v :: u :: h) l =
    match after V Vdec (v :: u :: h) [] s0 l with
    | Some r => Jd t sigma [(1, al)] h u (v :: r)
    | None => 0
    end.
  Proof. reflexivity. Qed.

  Lemma cont_off : forall t sigma al q l, ~ In q (steps [] s0 l) -> cont t sigma al q l == 0.
  Proof.
    intros t sigma al q l Hn. destruct q as [| v [| u h]]; try reflexivity.
    rewrite cont_eq. destruct (after V Vdec (v :: u :: h) [] s0 l) as [r |] eqn:Ha; [| reflexivity].
    exfalso. exact (Hn (after_in V Vdec l [] s0 _ r Ha)).
  Qed.

  Lemma cont_decomp : forall t sigma al v u h l,
    cont t sigma al (v :: u :: h) l ==
    sumL (fun q => if extb (v :: u :: h) q then w_at q * sbar sigma [(1, al)] (u :: h) q t else 0)
         (steps [] s0 l)
    + visits (v :: u :: h) l * dterm t (last l s0).
  Proof.
    intros t sigma al v u h l. unfold Game.visits.
    destruct (in_dec (list_eq_dec Vdec) (v :: u :: h) (steps [] s0 l)) as [Hin | Hnin].
    - destruct (in_after V Vdec l [] s0 _ Hin) as [r Ha].
      rewrite cont_eq, Ha.
      destruct (after_split V Vdec l [] s0 v u h r Ha) as [A [HA [Hlen Hlast]]].
      rewrite HA, sumL_app, Hlast.
      rewrite (sumL_zero _ A).
      2: { intros a Ha'. destruct (extb (v :: u :: h) a) eqn:He; [| reflexivity].
           apply extb_spec in He as [k ->]. specialize (Hlen _ Ha').
           rewrite app_length in Hlen. lia. }
      rewrite (sumL_ext _ (fun q => w_at q * sbar sigma [(1, al)] (u :: h) q t) (steps h u (v :: r))).
      2: { intros q Hq. rewrite (extb_steps v u h r q Hq). reflexivity. }
      rewrite Jd_decomp. ring.
    - rewrite cont_off by exact Hnin.
      rewrite sumL_zero; [ring |]. intros q Hq.
      destruct (extb (v :: u :: h) q) eqn:He; [| reflexivity].
      apply extb_spec in He as [k Hk]. exfalso. apply Hnin.
      apply (steps_prefix_closed V l [] s0 q k); [exact Hq | exact Hk | simpl; lia].
  Qed.

  (** Type [t]'s total continuation cost from [(al, q)], unnormalised. *)
  Definition N (t : T) (sigma : dstrat T V) (al : list T) (q : list V) : Q :=
    sumL (fun pl => fst pl * cont t sigma al q (snd pl)) (gamma t).

  Lemma N_zero : forall t sigma al q, In t types -> reach q (gamma t) == 0 -> N t sigma al q == 0.
  Proof.
    intros t sigma al q Ht Hr. unfold N. unfold Game.reach in Hr.
    destruct (gamma_valid t Ht) as [_ Hall].
    assert (Hnn : forall pl, In pl (gamma t) -> 0 <= fst pl * visits q (snd pl)).
    { intros [p l] Hin. simpl. destruct (Hall p l Hin) as [Hp _].
      unfold Game.visits. destruct (in_dec _ _ _); lra. }
    apply sumL_zero. intros [p l] Hin. simpl.
    pose proof (sumL_nonneg_zero _ _ Hnn Hr (p, l) Hin) as H0. simpl in H0.
    unfold Game.visits in H0. destruct (in_dec (list_eq_dec Vdec) q (steps [] s0 l)) as [Hq | Hq].
    - setoid_replace p with 0 by lra. ring.
    - rewrite cont_off by exact Hq. ring.
  Qed.

  Notation bayes := (bayes T types V Vdec s0 prior gamma).
  Notation on_path := (on_path T types V Vdec s0 prior gamma).

  Lemma CP_bayes : forall sigma al q, on_path q ->
    CP T types V Vdec w dterm s0 gamma bayes sigma al q ==
    sumL (fun t => prior t * N t sigma al q) types / Z q.
  Proof.
    intros sigma al q Hon. unfold CP, Qdiv. rewrite <- sumL_scale_r. apply sumL_ext. intros t Ht.
    unfold Game.bayes. destruct (Qlt_le_dec 0 (Z q)) as [Hz | Hz]; [| unfold Game.on_path in Hon; lra].
    unfold Game.condcost, Game.mass. fold (N t sigma al q).
    destruct (Qeq_dec (reach q (gamma t)) 0) as [H0 | H0].
    - rewrite (N_zero t sigma al q Ht H0), H0. unfold Qdiv. rewrite Qmult_0_r, Qmult_0_r, Qmult_0_l. ring.
    - assert (Hz0 : ~ Z q == 0) by (intros Hz0; rewrite Hz0 in Hz; discriminate).
      field. split; assumption.
  Qed.

  Lemma sum_pos : forall (A : Type) (f : A -> Q) l, 0 < sumL f l -> exists x, In x l /\ 0 < f x.
  Proof.
    intros A f. induction l as [| x l IH]; simpl; intros H; [discriminate |].
    destruct (Qlt_le_dec 0 (f x)) as [Hp | Hn]; [exists x; auto |].
    destruct (IH ltac:(lra)) as [y [Hy Hp]]. exists y. auto.
  Qed.

  Lemma on_path_step : forall q, on_path q ->
    exists t p l, In t types /\ In (p, l) (gamma t) /\ In q (steps [] s0 l).
  Proof.
    intros q Hon. unfold Game.on_path, Game.Z in Hon.
    destruct (sum_pos T _ types Hon) as [t [Ht Hm]].
    unfold Game.mass, Game.reach in Hm.
    destruct (Qlt_le_dec 0 (sumL (fun pl => fst pl * visits q (snd pl)) (gamma t))) as [Hr | Hr].
    - destruct (sum_pos _ _ _ Hr) as [[p l] [Hin Hv]]. simpl in Hv.
      unfold Game.visits in Hv. destruct (in_dec _ _ _) as [Hq | _]; [| lra].
      exists t, p, l. auto.
    - exfalso. pose proof (prior_nonneg t).
      assert (prior t * sumL (fun pl => fst pl * visits q (snd pl)) (gamma t) <= 0); [| lra].
      setoid_replace 0 with (prior t * 0) by ring. apply Qmul_le_l; assumption.
  Qed.

  (** The continuation payoff decomposes over the trie below [q]. *)
  Lemma N_decomp : forall sigma al v u h,
    sumL (fun t => prior t * N t sigma al (v :: u :: h)) types ==
    sumL (fun q => if extb (v :: u :: h) q
                   then w_at q * sumL (fun t => sbar sigma [(1, al)] (u :: h) q t * mass t q) types
                   else 0) trie
    + sumL (fun t => prior t * sumL (fun pl => fst pl * (visits (v :: u :: h) (snd pl) * dterm t (last (snd pl) s0)))
                                    (gamma t)) types.
  Proof.
    intros sigma al v u h.
    rewrite (sumL_ext (fun q => if extb (v :: u :: h) q then _ else 0)
               (fun q => sumL (fun t => prior t * ((if extb (v :: u :: h) q
                                     then w_at q * sbar sigma [(1, al)] (u :: h) q t else 0) * reach q (gamma t))) types)).
    2: { intros q _. destruct (extb (v :: u :: h) q).
         - rewrite <- sumL_scale. apply sumL_ext. intros t _. unfold Game.mass. ring.
         - symmetry. apply sumL_zero. intros t _. ring. }
    rewrite <- sumL_swap, <- sumL_plus. apply sumL_ext. intros t Ht.
    rewrite sumL_scale, <- Qmult_plus_distr_r.
    rewrite <- (trie_sum (fun q => if extb (v :: u :: h) q then w_at q * sbar sigma [(1, al)] (u :: h) q t else 0)
                 (gamma t) trie trie_nodup)
      by (intros p l q Hpl Hq; exact (trie_complete t p l q Ht Hpl Hq)).
    unfold N. rewrite <- sumL_plus.
    enough (H : sumL (fun pl => fst pl * cont t sigma al (v :: u :: h) (snd pl)) (gamma t) ==
                sumL (fun pl => fst pl * sumL (fun q => if extb (v :: u :: h) q
                                  then w_at q * sbar sigma [(1, al)] (u :: h) q t else 0) (steps [] s0 (snd pl))
                     + fst pl * (visits (v :: u :: h) (snd pl) * dterm t (last (snd pl) s0))) (gamma t))
      by (rewrite H; reflexivity).
    apply sumL_ext. intros [p l] _. cbn [fst snd]. rewrite cont_decomp. ring.
  Qed.

  (** L3.3: greedy on the masses at every on-path prefix ⇒ sequentially
      rational at every on-path information set, whatever the Defender's own
      past allocations, against every deviation, under Bayes beliefs. *)
  Theorem greedy_seq_rational : forall s, (forall h u v, dist (s h u v)) ->
    (forall q, on_path q -> greedy s q) ->
    forall q, on_path q -> forall al sigma', admissible T types V sigma' ->
      CP T types V Vdec w dterm s0 gamma bayes sigma' al q <=
      CP T types V Vdec w dterm s0 gamma bayes (of_w T V s) al q.
  Proof.
    intros s Hs Hg q Hon al sigma' Hadm.
    destruct (on_path_step q Hon) as [t0 [p0 [l0 [Ht0 [Hpl0 Hq0]]]]].
    destruct (steps_shape V l0 [] s0 q Hq0) as [v [k Hk]].
    destruct (k ++ [s0]) as [| u h] eqn:Hks; [destruct k; discriminate |]. subst q.
    rewrite !CP_bayes by exact Hon.
    unfold Game.on_path in Hon. unfold Qdiv.
    apply Qmult_le_compat_r; [| apply Qlt_le_weak, Qinv_lt_0_compat; exact Hon].
    rewrite !N_decomp. apply Qplus_le_compat; [| apply Qle_refl].
    apply sumL_le. intros q Hq.
    destruct (extb (v :: u :: h) q) eqn:He; [| apply Qle_refl].
    apply extb_spec in He as [k' ->].
    assert (Htl : exists k'', tl (k' ++ v :: u :: h) = k'' ++ u :: h).
    { destruct k' as [| x k']; [exists []; reflexivity | exists (k' ++ [v]); simpl; rewrite <- app_assoc; reflexivity]. }
    destruct Htl as [k'' Htl].
    assert (Hadm_s : admissible T types V (of_w T V s)) by (intros al' h' u' v'; apply Hs).
    assert (Hok1 : odist_ok [(1, al)]) by (split; [simpl; ring | intros ra [<- | []]; simpl; lra]).
    apply prefix_le; [exact Hs | exact Hadm | exact (trie_arc _ Hq) | apply Hg | |];
      rewrite Htl; apply Dat_ok; try discriminate; assumption.
  Qed.
End Defender.
