(** * Walk prefixes as reversed node lists: the steps of a walk, extension of
    a prefix, and sums over the walk trie.

    An information set of the Defender is a reversed walk prefix
    [v :: u :: h].  [steps h u l] lists the information sets a walk passes
    through; [extb q q'] says that [q'] extends [q]; [trie_sum] exchanges a
    sum over a mixture's walks and their steps with a sum over the trie. *)

From Coq Require Import QArith Lqa List Arith Lia.
Import ListNotations.
From DPP Require Import Sums Game.
Open Scope Q_scope.

Section Prefix.
  Variable V : Type.
  Variable Vdec : forall x y : V, {x = y} + {x <> y}.
  Notation steps := (steps V).
  Definition ldec := list_eq_dec Vdec.

  Lemma steps_shape : forall l h u q, In q (steps h u l) ->
    exists v k, q = v :: k ++ u :: h.
  Proof.
    induction l as [| v l IH]; intros h u q Hin; simpl in Hin; [destruct Hin |].
    destruct Hin as [<- | Hin].
    - exists v, []. reflexivity.
    - destruct (IH (u :: h) v q Hin) as [v' [k ->]].
      exists v', (k ++ [v]). rewrite <- app_assoc. reflexivity.
  Qed.

  Lemma steps_len : forall l h u q, In q (steps h u l) -> (2 + length h <= length q)%nat.
  Proof.
    intros l h u q Hin. destruct (steps_shape l h u q Hin) as [v [k ->]].
    simpl. rewrite app_length. simpl. lia.
  Qed.

  Lemma steps_nodup : forall l h u, NoDup (steps h u l).
  Proof.
    induction l as [| v l IH]; intros h u; simpl; constructor.
    - intros Hin. apply steps_len in Hin. simpl in Hin. lia.
    - apply IH.
  Qed.

  Lemma steps_pwalk : forall E isgoal l h u q, pwalk V E isgoal u l -> In q (steps h u l) ->
    exists v u' h', q = v :: u' :: h' /\ E u' v.
  Proof.
    intros E isgoal. induction l as [| v l IH]; intros h u q Hw Hin; simpl in *; [destruct Hin |].
    destruct Hw as [_ [Huv Hw]]. destruct Hin as [<- | Hin].
    - exists v, u, h. auto.
    - exact (IH (u :: h) v q Hw Hin).
  Qed.

  Lemma gwalk_pwalk : forall E isgoal l u, gwalk V E isgoal u l -> pwalk V E isgoal u l.
  Proof.
    intros E isgoal. induction l as [| v l IH]; intros u H; simpl in *; [exact I |].
    destruct H as [H1 [H2 H3]]. auto.
  Qed.

  (** ** Extension. *)
  Lemma skipn_app_len : forall (k a : list V), skipn (length k) (k ++ a) = a.
  Proof. induction k as [| x k IH]; intros a; simpl; [reflexivity | apply IH]. Qed.

  Definition extb (q q' : list V) : bool :=
    if ldec (skipn (length q' - length q) q') q then Nat.leb (length q) (length q') else false.

  Lemma extb_spec : forall q q', extb q q' = true <-> exists k, q' = k ++ q.
  Proof.
    intros q q'. unfold extb. split.
    - destruct (ldec (skipn (length q' - length q) q') q) as [Heq | _]; [| discriminate].
      intros _. exists (firstn (length q' - length q) q').
      rewrite <- Heq at 2. symmetry. apply firstn_skipn.
    - intros [k ->]. rewrite app_length.
      replace (length k + length q - length q)%nat with (length k) by lia.
      rewrite skipn_app_len.
      destruct (ldec q q) as [_ | Hn]; [| contradiction].
      apply Nat.leb_le. lia.
  Qed.

  Lemma length_neq : forall (a b : list V), length a <> length b -> a <> b.
  Proof. intros a b H Heq. subst. contradiction. Qed.

  (** If [q'] is a step of a walk and extends [q], and [q] is long enough to
      be a step itself, then [q] is a step of the walk too. *)
  Lemma app_same_len : forall (k k' a b : list V), k ++ a = k' ++ b -> length a = length b -> a = b.
  Proof.
    intros k k' a b H Hl.
    assert (Hk : length k = length k').
    { apply (f_equal (@length V)) in H. rewrite !app_length in H. lia. }
    apply (f_equal (skipn (length k))) in H.
    rewrite skipn_app_len in H. rewrite Hk, skipn_app_len in H. exact H.
  Qed.

  Lemma steps_prefix_closed : forall l h u q' k q,
    In q' (steps h u l) -> q' = k ++ q -> (2 + length h <= length q)%nat -> In q (steps h u l).
  Proof.
    induction l as [| v l IH]; intros h u q' k q Hin Hq Hlen; simpl in *; [destruct Hin |].
    destruct Hin as [<- | Hin].
    - left. destruct k as [| x k]; [simpl in Hq; exact Hq |].
      apply (f_equal (@length V)) in Hq. simpl in Hq. rewrite app_length in Hq. simpl in Hlen. lia.
    - destruct (Nat.eq_dec (length q) (2 + length h)) as [Heq | Hne].
      + left. destruct (steps_shape l (u :: h) v q' Hin) as [v' [k' Hk']].
        rewrite Hq in Hk'. symmetry.
        apply (app_same_len k (v' :: k') q (v :: u :: h)); [exact Hk' | simpl; lia].
      + right. apply (IH (u :: h) v q' k q Hin Hq). simpl. lia.
  Qed.

  (** ** [after]: the rest of a walk after one of its steps. *)
  Lemma in_after : forall l h u q, In q (steps h u l) -> exists r, after V Vdec q h u l = Some r.
  Proof.
    induction l as [| v l IH]; intros h u q Hin; cbn [after steps In] in *; [destruct Hin |].
    destruct (list_eq_dec Vdec (v :: u :: h) q) as [_ | Hne]; [eexists; reflexivity |].
    destruct Hin as [Heq | Hin]; [contradiction | exact (IH (u :: h) v q Hin)].
  Qed.

  Lemma after_in : forall l h u q r, after V Vdec q h u l = Some r -> In q (steps h u l).
  Proof.
    induction l as [| v l IH]; intros h u q r H; cbn [after steps In] in *; [discriminate |].
    destruct (list_eq_dec Vdec (v :: u :: h) q) as [<- | Hne]; [left; reflexivity |].
    right. exact (IH (u :: h) v q r H).
  Qed.

  (** A walk through [q = v :: u :: h] splits into the steps before [q]
      (all shorter than [q]) and the steps of the rest [v :: r] from [u]. *)
  Lemma after_split : forall l h0 u0 v u h r,
    after V Vdec (v :: u :: h) h0 u0 l = Some r ->
    exists A, steps h0 u0 l = A ++ steps h u (v :: r) /\
              (forall a, In a A -> (length a < length (v :: u :: h))%nat) /\
              last l u0 = last (v :: r) u.
  Proof.
    induction l as [| x l IH]; intros h0 u0 v u h r H; cbn [after] in H; [discriminate |].
    destruct (list_eq_dec Vdec (x :: u0 :: h0) (v :: u :: h)) as [Heq | Hne].
    - inversion Heq; subst. inversion H; subst.
      exists []. split; [reflexivity | split; [intros a [] | reflexivity]].
    - destruct (IH (u0 :: h0) x v u h r H) as [A [HA [Hlen Hlast]]].
      exists ((x :: u0 :: h0) :: A). split; [| split].
      + simpl. rewrite HA. reflexivity.
      + intros a [<- | Ha]; [| exact (Hlen a Ha)].
        pose proof (after_in l (u0 :: h0) x (v :: u :: h) r H) as Hin.
        apply steps_len in Hin. simpl in *. lia.
      + rewrite last_cons. exact Hlast.
  Qed.

  (** ** Sums over a duplicate-free list that contains a sublist. *)
  Definition inq (x : list V) (L : list (list V)) : Q := if in_dec ldec x L then 1 else 0.

  Lemma sum_incl : forall (F : list V -> Q) L P, NoDup L -> NoDup P -> incl L P ->
    sumL F L == sumL (fun x => F x * inq x L) P.
  Proof.
    intros F. induction L as [| y L IH]; intros P HL HP Hinc; simpl.
    - symmetry. apply sumL_zero. intros x _. unfold inq. simpl. ring.
    - inversion HL as [| y' L' Hy HL']; subst.
      rewrite (IH P HL' HP (fun x Hx => Hinc x (or_intror Hx))).
      rewrite (sumL_ext (fun x => F x * inq x (y :: L))
                        (fun x => F x * ind ldec y x + F x * inq x L)).
      + rewrite sumL_plus, (sumL_ind ldec F P y HP (Hinc y (or_introl eq_refl))). ring.
      + intros x _. unfold inq, ind.
        destruct (in_dec ldec x L) as [Hin | Hnin];
        destruct (in_dec ldec x (y :: L)) as [Hin' | Hnin'];
        destruct (ldec x y) as [Heq | Hne]; try ring.
        * subst. contradiction.
        * exfalso. apply Hnin'. right. exact Hin.
        * exfalso. apply Hnin'. right. exact Hin.
        * exfalso. destruct Hin' as [Heq | Hin']; [apply Hne; symmetry; exact Heq | contradiction].
        * exfalso. apply Hnin'. left. symmetry. exact Heq.
  Qed.
End Prefix.
