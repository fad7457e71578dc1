(** * L3.2, the converse: a Defender that looks at the walk only and is
    optimal against the profile's Attacker is greedy on the masses at every
    on-path prefix (weights positive).  With [Defender.greedy_optimal] and
    [Defender.greedy_seq_rational]: greedy on the masses at every on-path
    prefix ⇔ optimal ⇔ optimal and sequentially rational. *)

From Coq Require Import QArith Lqa List Arith Lia.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel Defender.
Open Scope Q_scope.

Section Converse.
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
  Hypothesis w_pos : forall u v, E u v -> 0 < w u v.
  Hypothesis prior_nonneg : forall t, 0 <= prior t.
  Variable gamma : T -> mixture V.
  Hypothesis gamma_valid : forall t, In t types -> valid_mixture V E isgoal s0 (gamma t).

  Lemma w_nonneg : forall u v, E u v -> 0 <= w u v.
  Proof. intros u v H. pose proof (w_pos u v H). lra. Qed.

  Notation mass := (mass T V Vdec s0 prior gamma).
  Notation trie := (trie T types V Vdec s0 gamma).

  (** The deviation: at the prefix [q] move σ's weight on [t] to [t']. *)
  Definition moved (s : wstrat T V) (q : list V) (t t' : T) : wstrat T V :=
    fun h u v x =>
      if list_eq_dec Vdec (v :: u :: h) q then
        (if Tdec x t then 0 else if Tdec x t' then s h u v t' + s h u v t else s h u v x)
      else s h u v x.

  Lemma moved_dist : forall s q t t', (forall h u v, dist T types (s h u v)) -> In t types ->
    In t' types -> t <> t' -> forall h u v, dist T types (moved s q t t' h u v).
  Proof.
    intros s q t t' Hs Ht Ht' Hne h u v. unfold moved.
    destruct (list_eq_dec Vdec (v :: u :: h) q) as [_ | _]; [| apply Hs].
    destruct (Hs h u v) as [H0 H1]. split.
    - intros x. destruct (Tdec x t); [lra |]. destruct (Tdec x t'); [pose proof (H0 t); pose proof (H0 t'); lra | apply H0].
    - rewrite <- H1.
      rewrite (sumL_ext _ (fun x => s h u v x + (s h u v t * ind Tdec t' x - s h u v t * ind Tdec t x))).
      + rewrite sumL_plus, sumL_minus.
        rewrite (sumL_ind Tdec (fun _ => s h u v t) types t' types_nodup Ht').
        rewrite (sumL_ind Tdec (fun _ => s h u v t) types t types_nodup Ht). ring.
      + intros x _. unfold ind. destruct (Tdec x t) as [-> | Hxt].
        * destruct (Tdec t t') as [Heq | _]; [contradiction |]. ring.
        * destruct (Tdec x t') as [-> | Hxt']; ring.
  Qed.

  Lemma sumL_single : forall (A : Type) (Adec : forall x y : A, {x = y} + {x <> y}) (f : A -> Q) l a,
    NoDup l -> In a l -> (forall x, In x l -> x <> a -> f x == 0) -> sumL f l == f a.
  Proof.
    intros A Adec f l a Hnd Ha Hz.
    rewrite (sumL_ext f (fun x => f x * ind Adec a x)).
    - apply (sumL_ind Adec f l a Hnd Ha).
    - intros x Hx. unfold ind. destruct (Adec x a) as [-> | Hne]; [ring | rewrite (Hz x Hx Hne); ring].
  Qed.

  Theorem optimal_greedy : forall s, (forall h u v, dist T types (s h u v)) ->
    defender_optimal T types V w dterm s0 prior gamma (of_w T V s) ->
    forall q, on_path T types V Vdec s0 prior gamma q -> greedy T types V Vdec s0 prior gamma s q.
  Proof.
    intros s Hs Hopt q Hon t t' Ht Ht' Hpos.
    destruct (Qlt_le_dec (mass t q) (mass t' q)) as [Hlt | Hle]; [exfalso | exact Hle].
    assert (Hne : t <> t') by (intros ->; lra).
    destruct (on_path_step T types V Vdec s0 prior prior_nonneg gamma q Hon) as [t0 [p0 [l0 [Ht0 [Hpl0 Hq0]]]]].
    assert (Hqt : In q trie) by exact (trie_complete T types V Vdec s0 gamma t0 p0 l0 q Ht0 Hpl0 Hq0).
    destruct (trie_arc T types V Vdec E isgoal s0 gamma gamma_valid q Hqt) as [v [u [h [Hq Huv]]]].
    subst q.
    set (s' := moved s (v :: u :: h) t t').
    assert (Hs' : forall h' u' v', dist T types (s' h' u' v')) by (apply moved_dist; assumption).
    assert (Hadm : admissible T types V (of_w T V s')) by (intros al h' u' v'; apply Hs').
    specialize (Hopt (of_w T V s') Hadm).
    rewrite !(Upay_decomp T types V Vdec w dterm s0 prior gamma) in Hopt.
    (* on the trie the averages are the strategies themselves *)
    assert (Hbar : forall sg, (forall h' u' v', dist T types (sg h' u' v')) -> forall q' x, In q' trie ->
              sbar T types V Vdec (of_w T V sg) (D0 T) [s0] q' x == sig_at T V (of_w T V sg) [] q' x).
    { intros sg Hsg q' x Hq'. apply sbar_of_w.
      unfold Defender.trie in Hq'. apply nodup_In, in_flat_map in Hq' as [t1 [_ Hq']].
      apply in_flat_map in Hq' as [[p1 l1] [_ Hq']].
      destruct (steps_shape V l1 [] s0 _ Hq') as [v1 [k Hk]]. rewrite Hk. cbn [tl].
      apply Dat_ok; [intros al h' u' v'; apply Hsg | destruct k; discriminate |].
      unfold odist_ok, D0. simpl. split; [ring | intros ra [<- | []]; simpl; lra]. }
    set (F := fun sg q' => w_at V w q' * sumL (fun x => sig_at T V (of_w T V sg) [] q' x * mass x q') types).
    assert (HF : forall sg, (forall h' u' v', dist T types (sg h' u' v')) ->
              sumL (fun q' => w_at V w q' * sumL (fun x => sbar T types V Vdec (of_w T V sg) (D0 T) [s0] q' x * mass x q') types) trie
              == sumL (F sg) trie).
    { intros sg Hsg. apply sumL_ext. intros q' Hq'. unfold F. apply Qmult_comp; [reflexivity |].
      apply sumL_ext. intros x _. rewrite (Hbar sg Hsg q' x Hq'). reflexivity. }
    rewrite (HF s' Hs'), (HF s Hs) in Hopt.
    assert (Hdiff : sumL (F s') trie - sumL (F s) trie ==
                    w u v * (s h u v t * mass t' (v :: u :: h) - s h u v t * mass t (v :: u :: h))).
    { rewrite <- sumL_minus.
      rewrite (sumL_single (list V) (list_eq_dec Vdec) _ trie (v :: u :: h)
                 (trie_nodup T types V Vdec s0 gamma) Hqt).
      - unfold F. cbn [w_at sig_at of_w]. unfold s', moved.
        destruct (list_eq_dec Vdec (v :: u :: h) (v :: u :: h)) as [_ | Hc]; [| contradiction].
        assert (Hd : forall c a b : Q, c * a - c * b == c * (a - b)) by (intros; ring).
        rewrite Hd. apply Qmult_comp; [reflexivity |].
        rewrite <- sumL_minus.
        rewrite (sumL_ext _ (fun x => (s h u v t * mass t' (v :: u :: h)) * ind Tdec t' x
                                      - (s h u v t * mass t (v :: u :: h)) * ind Tdec t x)).
        + rewrite sumL_minus, (sumL_ind Tdec (fun _ => s h u v t * mass t' (v :: u :: h)) types t' types_nodup Ht').
          rewrite (sumL_ind Tdec (fun _ => s h u v t * mass t (v :: u :: h)) types t types_nodup Ht). reflexivity.
        + intros x _. unfold of_w. cbv beta.
          destruct (list_eq_dec Vdec (v :: u :: h) (v :: u :: h)) as [_ | Hc']; [| contradiction].
          unfold ind. destruct (Tdec x t) as [-> | Hxt].
          * destruct (Tdec t t') as [Heq | _]; [contradiction |]. ring.
          * destruct (Tdec x t') as [-> | Hxt']; ring.
      - intros q' _ Hq'. unfold F. destruct q' as [| v' [| u' h']]; cbn [w_at sig_at of_w]; [ring | ring |].
        unfold s', moved, of_w. cbv beta.
        destruct (list_eq_dec Vdec (v' :: u' :: h') (v :: u :: h)) as [Heq | _]; [contradiction | ring]. }
    cbn [sig_at] in Hpos. unfold of_w in Hpos.
    pose proof (w_pos u v Huv) as Hw.
    assert (0 < w u v * (s h u v t * mass t' (v :: u :: h) - s h u v t * mass t (v :: u :: h))).
    { apply Qmult_lt_0_compat; [exact Hw |].
      setoid_replace (s h u v t * mass t' (v :: u :: h) - s h u v t * mass t (v :: u :: h))
        with (s h u v t * (mass t' (v :: u :: h) - mass t (v :: u :: h))) by ring.
      apply Qmult_lt_0_compat; lra. }
    lra.
  Qed.
End Converse.
