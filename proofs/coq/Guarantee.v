(** * The N-goal guarantee rule: what the kernel's certificates prove, and
    the equilibrium modulo NR.2.

    The rule (docs/formats.md §2b, proofs/NRULE.md) keeps a state [r]
    (r_0 = h, r ← r − w σ) and plays at the step into [u] of weight [w] the
    lexicographic minimum, in the priority order [o], of
    F = {σ ∈ Δ : a·σ ≥ (a·r − m_a(u)) / w for every normal a}.
    - [lexmin_of_certificate]: a primal point σ ∈ F and one dual per stage
      (the kernel's [guarantee._step]) prove σ is that lexicographic minimum
      (weak LP duality per stage; the last stage is pinned by Σσ = 1), and
      [lexmin_unique]: there is only one, so the rule's σ is the certified one.
    - [cover_bound]: the containment step of the arc condition: a cover μ ≥ 0
      with Σ μ_a a = y bounds y·r by μ·m(v) on F_v = {r : a·r ≤ m_a(v)}, so the
      kernel's arc test gives λ·(A r − m(u)) ≤ w for every r ∈ F_v and every
      direction λ it tests.
    - [guarantee_pbne]: with NR.2 — the guarantee itself, that h ∈ F_{s0} and
      the arc condition make every walk cost type θ at least h_θ — taken as an
      explicit hypothesis (the one step that stays a written proof,
      proofs/NRULE.md), certified σ on the profile's prefixes, U_θ ≤ h_θ and
      greedy masses give a weak PBNE of the untruncated game. *)

From Coq Require Import QArith Lqa List Bool Arith Lia Permutation.
Import ListNotations.
From DPP Require Import Sums Game Prefix Tel Defender Pbne.
Open Scope Q_scope.

Lemma sumL_perm : forall (A : Type) (f : A -> Q) l l', Permutation l l' -> sumL f l == sumL f l'.
Proof.
  intros A f l l' H. induction H; simpl; try reflexivity.
  - rewrite IHPermutation. reflexivity.
  - ring.
  - rewrite IHPermutation1, IHPermutation2. reflexivity.
Qed.

(** ** The stage LPs of the lexicographic minimum. *)
Section Lex.
  Variable N : nat.
  Notation idx := (seq 0 N).
  Variable A : list (list Q).               (* the normals, each a list of N numbers *)
  Notation K := (length A).
  Variable beta : nat -> Q.                 (* one bound per normal *)
  Variable o : list nat.                    (* the priority order *)
  Hypothesis o_perm : Permutation o idx.

  Definition dotv (a : list Q) (x : nat -> Q) : Q := sumL (fun i => nth i a 0 * x i) idx.

  Definition inF (x : nat -> Q) : Prop :=
    (forall i, In i idx -> 0 <= x i) /\ sumL x idx == 1 /\
    (forall k, (k < K)%nat -> beta k <= dotv (nth k A []) x).

  Definition ord (j : nat) : nat := nth j o O.

  Definition lexmin (s : nat -> Q) : Prop :=
    inF s /\ forall k, (k < N)%nat -> forall x, inF x ->
      (forall j, (j < k)%nat -> x (ord j) == s (ord j)) -> s (ord k) <= x (ord k).

  Lemma o_len : length o = N.
  Proof. rewrite (Permutation_length o_perm). apply seq_length. Qed.

  Lemma ord_in : forall j, (j < N)%nat -> In (ord j) idx.
  Proof.
    intros j Hj. apply (Permutation_in _ o_perm). apply nth_In. rewrite o_len. exact Hj.
  Qed.

  (** Stage [k]'s dual: y ≥ 0 (one per normal), z (for Σσ = 1) and [fix]
      (one per earlier stage, for σ_{o_j} fixed). *)
  Definition coef (y : list Q) (z : Q) (fx : list Q) (k i : nat) : Q :=
    sumL (fun a => nth a y 0 * nth i (nth a A []) 0) (seq 0 K) + z +
    sumL (fun j => nth j fx 0 * ind Nat.eq_dec (ord j) i) (seq 0 k).

  Definition dual_ok (s : nat -> Q) (k : nat) (y : list Q) (z : Q) (fx : list Q) : Prop :=
    (forall a, (a < K)%nat -> 0 <= nth a y 0) /\
    (forall i, In i idx -> coef y z fx k i <= ind Nat.eq_dec (ord k) i) /\
    s (ord k) <= sumL (fun a => nth a y 0 * beta a) (seq 0 K) + z +
                 sumL (fun j => nth j fx 0 * s (ord j)) (seq 0 k).

  (** Weak duality of one stage. *)
  Theorem stage_bound : forall s k y z fx x, (k < N)%nat -> dual_ok s k y z fx -> inF x ->
    (forall j, (j < k)%nat -> x (ord j) == s (ord j)) -> s (ord k) <= x (ord k).
  Proof.
    intros s k y z fx x Hk [Hy [Hc Hobj]] [Hx0 [Hx1 HxA]] Hfix.
    assert (Hxk : x (ord k) == sumL (fun i => x i * ind Nat.eq_dec (ord k) i) idx).
    { symmetry. apply (sumL_ind Nat.eq_dec x idx (ord k)); [apply seq_NoDup | exact (ord_in k Hk)]. }
    assert (Hge : sumL (fun i => x i * coef y z fx k i) idx <= x (ord k)).
    { rewrite Hxk. apply sumL_le. intros i Hi. apply Qmul_le_l; [apply Hx0; exact Hi | apply Hc; exact Hi]. }
    unfold coef in Hge.
    rewrite (sumL_ext _ (fun i => sumL (fun a => nth a y 0 * (nth i (nth a A []) 0 * x i)) (seq 0 K)
                               + z * x i
                               + sumL (fun j => nth j fx 0 * (x i * ind Nat.eq_dec (ord j) i)) (seq 0 k)))
      in Hge.
    2: { intros i _. rewrite !Qmult_plus_distr_r.
         rewrite <- (sumL_scale (x i) (fun a => nth a y 0 * nth i (nth a A []) 0)).
         rewrite <- (sumL_scale (x i) (fun j => nth j fx 0 * ind Nat.eq_dec (ord j) i)).
         apply Qplus_comp; [apply Qplus_comp; [apply sumL_ext; intros; ring | ring] |].
         apply sumL_ext; intros; ring. }
    rewrite !sumL_plus, sumL_swap, (sumL_scale z), Hx1 in Hge.
    rewrite (sumL_swap (fun i j => nth j fx 0 * (x i * ind Nat.eq_dec (ord j) i))) in Hge.
    rewrite (sumL_ext (fun j => sumL (fun i => nth j fx 0 * (x i * ind Nat.eq_dec (ord j) i)) idx)
                      (fun j => nth j fx 0 * s (ord j)) (seq 0 k)) in Hge.
    2: { intros j Hj. apply in_seq in Hj. rewrite sumL_scale.
         rewrite (sumL_ind Nat.eq_dec x idx (ord j)); [| apply seq_NoDup | apply ord_in; lia].
         rewrite (Hfix j ltac:(lia)). reflexivity. }
    assert (Hyb : sumL (fun a => nth a y 0 * beta a) (seq 0 K) <=
                  sumL (fun a => sumL (fun i => nth a y 0 * (nth i (nth a A []) 0 * x i)) idx) (seq 0 K)).
    { apply sumL_le. intros a Ha. apply in_seq in Ha. rewrite sumL_scale.
      apply Qmul_le_l; [apply Hy; lia |]. apply HxA. lia. }
    lra.
  Qed.

  (** The last stage is pinned by Σσ = 1. *)
  Lemma last_stage : forall s x, inF s -> inF x -> (forall j, (j < N - 1)%nat -> x (ord j) == s (ord j)) ->
    (0 < N)%nat -> x (ord (N - 1)) == s (ord (N - 1)).
  Proof.
    intros s x [_ [Hs _]] [_ [Hx _]] Hfix HN.
    assert (Hp : Permutation (map ord (seq 0 N)) idx).
    { unfold ord. replace (map (fun j => nth j o O) (seq 0 N)) with o; [exact o_perm |].
      rewrite <- o_len. symmetry. apply map_nth_seq. }
    assert (Hsx : sumL x (map ord (seq 0 N)) == sumL s (map ord (seq 0 N))).
    { rewrite !(sumL_perm _ _ _ _ Hp), Hx, Hs. reflexivity. }
    replace N with (S (N - 1)) in Hsx by lia. rewrite seq_S, map_app, !sumL_app in Hsx. simpl in Hsx.
    rewrite !sumL_map in Hsx.
    rewrite (sumL_ext (fun j => x (ord j)) (fun j => s (ord j))) in Hsx.
    - lra.
    - intros j Hj. apply in_seq in Hj. apply Hfix. lia.
  Qed.

  (** [lexmin_of_certificate]: a primal point and one dual per stage but the last. *)
  Theorem lexmin_of_certificate : forall s (duals : nat -> list Q * Q * list Q),
    inF s -> (forall k, (k < N - 1)%nat -> let '(y, z, fx) := duals k in dual_ok s k y z fx) ->
    lexmin s.
  Proof.
    intros s duals Hs Hd. split; [exact Hs |]. intros k Hk x Hx Hfix.
    destruct (Nat.lt_ge_cases k (N - 1)) as [Hlt | Hge].
    - specialize (Hd k Hlt). destruct (duals k) as [[y z] fx].
      exact (stage_bound s k y z fx x Hk Hd Hx Hfix).
    - assert (k = N - 1)%nat by lia. subst k.
      rewrite (last_stage s x Hs Hx (fun j Hj => Hfix j Hj) ltac:(lia)). apply Qle_refl.
  Qed.

  Theorem lexmin_unique : forall s s', lexmin s -> lexmin s' -> forall i, In i idx -> s i == s' i.
  Proof.
    intros s s' [Hs Hls] [Hs' Hls'].
    assert (Hk : forall k, (k < N)%nat -> s (ord k) == s' (ord k)).
    { intros k. induction k as [k IH] using lt_wf_ind. intros Hk.
      assert (H1 := Hls k Hk s' Hs' (fun j Hj => Qeq_sym _ _ (IH j Hj ltac:(lia)))).
      assert (H2 := Hls' k Hk s Hs (fun j Hj => IH j Hj ltac:(lia))). lra. }
    intros i Hi. apply (Permutation_in _ (Permutation_sym o_perm)) in Hi.
    destruct (In_nth o i O Hi) as [k [Hkl Heq]]. rewrite o_len in Hkl.
    rewrite <- Heq. exact (Hk k Hkl).
  Qed.
End Lex.

(** ** The kernel's test of one step's σ ([guarantee._step]), executable:
    σ ∈ F, and per stage k < N − 1 a dual (y, z, fix) that is feasible and
    reaches σ_{o_k}. *)
Definition stage_check (N : nat) (A : list (list Q)) (beta : list Q) (o : list nat) (sg : list Q)
    (duals : list (list Q * Q * list Q)) : bool :=
  let K := length A in
  let sv := fun i => nth i sg 0 in
  let ord := fun j => nth j o O in
  Nat.eqb (length sg) N && forallb (fun x => Qle_bool 0 x) sg &&
  Qeq_bool (sumL sv (seq 0 N)) 1 &&
  forallb (fun k => Qle_bool (nth k beta 0) (sumL (fun i => nth i (nth k A []) 0 * sv i) (seq 0 N))) (seq 0 K) &&
  Nat.eqb (length duals) (N - 1) &&
  forallb (fun k =>
    let '(y, z, fx) := nth k duals ([], 0, []) in
    forallb (fun a => Qle_bool 0 (nth a y 0)) (seq 0 K) &&
    forallb (fun i => Qle_bool (sumL (fun a => nth a y 0 * nth i (nth a A []) 0) (seq 0 K) + z +
                                sumL (fun j => nth j fx 0 * ind Nat.eq_dec (ord j) i) (seq 0 k))
                               (ind Nat.eq_dec (ord k) i)) (seq 0 N) &&
    Qle_bool (sv (ord k)) (sumL (fun a => nth a y 0 * nth a beta 0) (seq 0 K) + z +
                           sumL (fun j => nth j fx 0 * sv (ord j)) (seq 0 k)))
    (seq 0 (N - 1)).

Theorem stage_check_lexmin : forall N A beta o sg duals, Permutation o (seq 0 N) ->
  stage_check N A beta o sg duals = true ->
  lexmin N A (fun k => nth k beta 0) o (fun i => nth i sg 0).
Proof.
  intros N A beta o sg duals Hp H. unfold stage_check in H. cbv zeta in H.
  repeat rewrite andb_true_iff in H. destruct H as [[[[[Hl Hnn] Hsum] HF] _] Hd].
  apply Nat.eqb_eq in Hl. rewrite forallb_forall in Hnn, HF, Hd.
  apply (lexmin_of_certificate N A _ o Hp _ (fun k => nth k duals ([], 0, []))).
  - split; [| split].
    + intros i Hi. apply in_seq in Hi. apply Qle_bool_iff, Hnn, nth_In. lia.
    + apply Qeq_bool_iff. exact Hsum.
    + intros k Hk. apply Qle_bool_iff, HF, in_seq. lia.
  - intros k Hk. specialize (Hd k (proj2 (in_seq _ _ _) (conj (Nat.le_0_l k) Hk))).
    destruct (nth k duals ([], 0, [])) as [[y z] fx].
    repeat rewrite andb_true_iff in Hd. destruct Hd as [[Hy Hc] Hobj].
    rewrite forallb_forall in Hy, Hc. split; [| split].
    + intros a Ha. apply Qle_bool_iff, Hy, in_seq. lia.
    + intros i Hi. apply Qle_bool_iff, Hc, Hi.
    + apply Qle_bool_iff. exact Hobj.
Qed.

(** ** The containment step of the arc condition. *)
Section Cover.
  Variable N : nat.
  Variable A : list (list Q).
  Variable mv : list Q.                     (* m_a(v), one per normal *)
  Variable r : nat -> Q.
  Hypothesis r_in : forall k, (k < length A)%nat -> dotv N (nth k A []) r <= nth k mv 0.

  (** A cover μ ≥ 0 of the direction [y] (Σ μ_a a = y) bounds y·r on F_v. *)
  Theorem cover_bound : forall (mu : list Q) (y : nat -> Q),
    (forall k, (k < length A)%nat -> 0 <= nth k mu 0) ->
    (forall i, In i (seq 0 N) -> sumL (fun k => nth k mu 0 * nth i (nth k A []) 0) (seq 0 (length A)) == y i) ->
    sumL (fun i => y i * r i) (seq 0 N) <= sumL (fun k => nth k mu 0 * nth k mv 0) (seq 0 (length A)).
  Proof.
    intros mu y Hmu Hy.
    rewrite (sumL_ext (fun i => y i * r i)
               (fun i => sumL (fun k => nth k mu 0 * (nth i (nth k A []) 0 * r i)) (seq 0 (length A)))).
    2: { intros i Hi. rewrite <- (Hy i Hi), <- sumL_scale_r. apply sumL_ext. intros k _. ring. }
    rewrite sumL_swap. apply sumL_le. intros k Hk. apply in_seq in Hk.
    rewrite sumL_scale. apply Qmul_le_l; [apply Hmu; lia | apply r_in; lia].
  Qed.
End Cover.

Lemma lexmin_ext : forall N A beta beta' o s, (forall k, beta k == beta' k) ->
  lexmin N A beta o s -> lexmin N A beta' o s.
Proof.
  intros N A beta beta' o s Hb [[H0 [H1 H2]] Hl]. split.
  - split; [exact H0 | split; [exact H1 |]]. intros k Hk. rewrite <- Hb. apply H2, Hk.
  - intros k Hk x [X0 [X1 X2]] Hfix. apply Hl; [exact Hk | | exact Hfix].
    split; [exact X0 | split; [exact X1 |]]. intros j Hj. rewrite Hb. apply X2, Hj.
Qed.

(** ** The guarantee rule in the game, and the equilibrium modulo NR.2. *)
Section Rule.
  Variable N : nat.
  Notation types := (seq 0 N).
  Variable V : Type.
  Variable Vdec : forall x y : V, {x = y} + {x <> y}.
  Variable E : V -> V -> Prop.
  Variable w : V -> V -> Q.
  Variable isgoal : V -> bool.
  Variable dterm : nat -> V -> Q.
  Variable s0 : V.
  Variable prior : nat -> Q.
  Hypothesis w_nonneg : forall u v, E u v -> 0 <= w u v.
  Hypothesis dterm_nonneg : forall t g, 0 <= dterm t g.
  Hypothesis prior_nonneg : forall t, 0 <= prior t.
  Variable gamma : nat -> mixture V.
  Hypothesis gamma_valid : forall t, In t types -> valid_mixture V E isgoal s0 (gamma t).

  Variable A : list (list Q).               (* the normals *)
  Variable m : V -> list Q.                 (* the labels m_a(v) *)
  Variable h0 : nat -> Q.                   (* the rule's vector h *)
  Variable o : list nat.                    (* the priority order *)
  Hypothesis o_perm : Permutation o types.

  (** The rule as a Defender of the game: [s] with the rule's state [rstate]
      (after the prefix ending at [u]) plays the lexicographic minimum of F
      wherever F is not empty and the labels describe it ([Live]: finite
      labels, at every node a walk of the game visits), and a distribution
      everywhere. *)
  Variable s : wstrat nat V.
  Fixpoint rstate (h : list V) (u : V) : nat -> Q :=
    match h with
    | [] => h0
    | x :: h' => fun i => rstate h' x i - w x u * s h' x u i
    end.
  Definition betaF (r : nat -> Q) (v : V) (wt : Q) (k : nat) : Q :=
    (dotv N (nth k A []) r - nth k (m v) 0) / wt.
  Variable Live : V -> Prop.                (* where the labels describe F (finite) *)
  Hypothesis gamma_live : forall t p l, In t types -> In (p, l) (gamma t) -> forall x, In x l -> Live x.
  Hypothesis rule_dist : forall h u v, dist nat types (s h u v).
  Hypothesis rule_lexmin : forall h u v, E u v -> Live v ->
    (exists x, inF N A (betaF (rstate h u) v (w u v)) x) ->
    lexmin N A (betaF (rstate h u) v (w u v)) o (s h u v).

  (** NR.2, the one written-only step (proofs/NRULE.md): with h ∈ F_{s0} and
      the arc condition — which the kernel checks — every walk of the game
      costs type θ at least h_θ. *)
  Hypothesis NR2 : forall t, In t types -> forall l, gwalk V E isgoal s0 l -> h0 t <= J nat V w dterm t s [] s0 l.

  (** The kernel's certified σ at the steps of the profile's walks, and its
      state along them. *)
  Variable cert : list V -> nat -> Q.
  Fixpoint rc (h : list V) (u : V) : nat -> Q :=
    match h with
    | [] => h0
    | x :: h' => fun i => rc h' x i - w x u * cert (u :: x :: h') i
    end.
  Hypothesis cert_ok : forall t p l q v u h, In t types -> In (p, l) (gamma t) -> In q (steps V [] s0 l) ->
    q = v :: u :: h -> lexmin N A (betaF (rc h u) v (w u v)) o (cert q).

  Lemma betaF_ext : forall r r' v wt, (forall i, In i types -> r i == r' i) ->
    forall k, betaF r v wt k == betaF r' v wt k.
  Proof.
    intros r r' v wt Hr k. unfold betaF, dotv.
    rewrite (sumL_ext (fun i => nth i (nth k A []) 0 * r i) (fun i => nth i (nth k A []) 0 * r' i));
      [reflexivity |]. intros i Hi. rewrite Hr by exact Hi. reflexivity.
  Qed.

  (** Along a profile walk, the rule's σ and state are the certified ones. *)
  Lemma along : forall t p, In t types -> forall l0, In (p, l0) (gamma t) ->
    forall l h u, (forall q, In q (steps V h u l) -> In q (steps V [] s0 l0)) ->
    (forall x, In x l -> Live x) ->
    pwalk V E isgoal u l -> (forall i, In i types -> rstate h u i == rc h u i) ->
    forall q v' u' h', In q (steps V h u l) -> q = v' :: u' :: h' ->
      (forall i, In i types -> s h' u' v' i == cert q i) /\ (forall i, In i types -> rstate h' u' i == rc h' u' i).
  Proof.
    intros t p Ht l0 Hpl. induction l as [| v l IH]; intros h u Hsub Hlv Hw Hr q v' u' h' Hq Heq; [destruct Hq |].
    destruct Hw as [_ [Huv Hw]].
    assert (Hq0 := cert_ok t p l0 (v :: u :: h) v u h Ht Hpl (Hsub _ (or_introl eq_refl)) eq_refl).
    apply (lexmin_ext N A _ (betaF (rstate h u) v (w u v))) in Hq0;
      [| intros k; symmetry; apply betaF_ext; exact Hr].
    assert (Hs0 : lexmin N A (betaF (rstate h u) v (w u v)) o (s h u v)).
    { apply rule_lexmin; [exact Huv | apply Hlv; left; reflexivity |].
      exists (cert (v :: u :: h)). exact (proj1 Hq0). }
    assert (Heqs : forall i, In i types -> s h u v i == cert (v :: u :: h) i)
      by exact (lexmin_unique N A _ o o_perm _ _ Hs0 Hq0).
    destruct Hq as [<- | Hq].
    - inversion Heq; subst. split; assumption.
    - apply (IH (u :: h) v); [intros q' Hq'; apply Hsub; right; exact Hq' |
        intros x Hx; apply Hlv; right; exact Hx | exact Hw | | exact Hq | exact Heq].
      intros i Hi. simpl. rewrite (Hr i Hi), (Heqs i Hi). reflexivity.
  Qed.

  (** The kernel's costs: J along the walk with the certified σ. *)
  Fixpoint Jc (t : nat) (h : list V) (u : V) (l : list V) : Q :=
    match l with
    | [] => dterm t u
    | v :: l' => w u v * cert (v :: u :: h) t + Jc t (u :: h) v l'
    end.

  Definition Ucert (t : nat) : Q := sumL (fun pl => fst pl * Jc t [] s0 (snd pl)) (gamma t).

  Hypothesis U_ok : forall t, In t types -> Ucert t <= h0 t.
  Hypothesis greedy_cert : forall q v u h, on_path nat types V Vdec s0 prior gamma q -> q = v :: u :: h ->
    forall t t', In t types -> In t' types -> 0 < cert q t ->
      mass nat V Vdec s0 prior gamma t' q <= mass nat V Vdec s0 prior gamma t q.

  Lemma J_Jc : forall t p, In t types -> forall l0, In (p, l0) (gamma t) ->
    forall l h u, (forall q, In q (steps V h u l) -> In q (steps V [] s0 l0)) ->
    (forall x, In x l -> Live x) ->
    pwalk V E isgoal u l -> (forall i, In i types -> rstate h u i == rc h u i) ->
    J nat V w dterm t s h u l == Jc t h u l.
  Proof.
    intros t p Ht l0 Hpl. induction l as [| v l IH]; intros h u Hsub Hlv Hw Hr; simpl; [reflexivity |].
    destruct (along t p Ht l0 Hpl (v :: l) h u Hsub Hlv Hw Hr (v :: u :: h) v u h (or_introl eq_refl) eq_refl)
      as [Hs _].
    destruct Hw as [Hng [Huv Hw']].
    rewrite (Hs t Ht). rewrite (IH (u :: h) v); [reflexivity | | | exact Hw' |].
    - intros q Hq. apply Hsub. right. exact Hq.
    - intros x Hx. apply Hlv. right. exact Hx.
    - intros i Hi. simpl. rewrite (Hr i Hi), (Hs i Hi). reflexivity.
  Qed.

  Theorem guarantee_pbne :
    weak_pbne nat Nat.eq_dec types V Vdec E w isgoal dterm s0 prior gamma (of_w nat V s)
              (bayes nat types V Vdec s0 prior gamma).
  Proof.
    apply pbne_of_checks; try assumption.
    - apply seq_NoDup.
    - intros t Ht l Hl. apply (Qle_trans _ (h0 t)); [| exact (NR2 t Ht l Hl)].
      rewrite (Umix_of_w nat types V w dterm s0 t s (gamma t) rule_dist).
      apply (Qle_trans _ (Ucert t)); [| exact (U_ok t Ht)].
      unfold Ucert. apply Qle_lteq. right. apply sumL_ext. intros [p l0] Hin. simpl.
      destruct (gamma_valid t Ht) as [_ Hall]. destruct (Hall p l0 Hin) as [_ Hw].
      rewrite (J_Jc t p Ht l0 Hin l0 [] s0 (fun q Hq => Hq) (gamma_live t p l0 Ht Hin)
                 (gwalk_pwalk V E isgoal l0 s0 Hw) (fun i _ => Qeq_refl _)).
      reflexivity.
    - intros q Hon.
      destruct (on_path_step nat types V Vdec s0 prior prior_nonneg gamma q Hon) as [t [p [l0 [Ht [Hpl Hq]]]]].
      destruct (steps_shape V l0 [] s0 q Hq) as [v [k Hk]].
      destruct (k ++ [s0]) as [| u h] eqn:Hks; [destruct k; discriminate |]. subst q.
      destruct (gamma_valid t Ht) as [_ Hall]. destruct (Hall p l0 Hpl) as [_ Hw].
      destruct (along t p Ht l0 Hpl l0 [] s0 (fun q Hq => Hq) (gamma_live t p l0 Ht Hpl)
                  (gwalk_pwalk V E isgoal l0 s0 Hw) (fun i _ => Qeq_refl _) (v :: u :: h) v u h Hq eq_refl)
        as [Hs _].
      intros t1 t2 Ht1 Ht2 Hpos. cbn [sig_at of_w] in Hpos. rewrite (Hs t1 Ht1) in Hpos.
      exact (greedy_cert (v :: u :: h) v u h Hon eq_refl t1 t2 Ht1 Ht2 Hpos).
  Qed.
End Rule.
