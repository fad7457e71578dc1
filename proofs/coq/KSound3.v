(** * Soundness of the kernel, part 3: the Attacker check.  The witness's
    potentials, extended to every walk prefix by the closed forms off the
    trie, form a feasible potential on the prefix graph of the game (K.2
    item 5, K.3), so every game walk costs each type at least φ(start) ≥ U. *)

From Coq Require Import QArith Lqa List Bool Arith Lia ZArith.
Import ListNotations.
From DPP Require Import Sums Game Potential Distances Kernel KFacts KSound1 KSound2.
Open Scope Q_scope.

Lemma le_ext_ole : forall a b, le_ext a b = true <-> ole a b.
Proof.
  intros [x |] [y |]; simpl; split; intros H; try discriminate; try contradiction; auto.
  - apply Qle_bool_iff. exact H.
  - apply Qle_bool_iff. exact H.
Qed.

Section Attacker.
  Variable I : instance.
  Variable W : witness.
  Variable C : canon.
  Hypothesis Hi : instance_ok I = true.
  Hypothesis Hshape : dist_shape_ok I W = true.
  Hypothesis Hdist : distances_ok I W = true.
  Hypothesis Hreach : reach_ok I W = true.
  Hypothesis Hrule : rule_ok I (crule C).
  Variables (es : list (list nat * list Q)) (dflt : default) (gl : nat).
  Hypothesis Hcr : crule C = RTable es dflt gl.

  Notation D := (D W).
  Notation trie := (trie I C).
  Notation gsig := (gsig I W C).

  Definition exit_spec (t : nat) (e : exitp) : Prop :=
    match e with
    | ENone => tdefault C = DNone
    | EConst E => exists q, tdefault C = DDist q /\ arcs_ok I W t E E (nth t q 0) true = true
    | ESame => tdefault C = DProgress /\ t = tgoal C
    | EOther P Q => tdefault C = DProgress /\ t <> tgoal C /\ arcs_ok I W t P P 1 true = true /\
                    arcs_ok I W t Q Q 1 false = true /\
                    forallb (fun u => negb (alive I W u) || le_ext (get Q u) (match D (tgoal C) u with
                                        | Some d => oadd d (get P u) | None => None end)) (seq 0 (n I)) = true
    end.

  Ltac step H E := lazymatch type of H with
    | (if ?c then _ else _) = _ => destruct c eqn:E; [try discriminate |]
    | (match ?c with Some _ => _ | None => _ end) = _ => destruct c eqn:E; [| try discriminate]
    end.

  Lemma check_type_spec : forall t r, check_type I W C t r = None ->
    exists (xs : list (option BinNums.Z)) e, exit_spec t e /\ trie_ok I W C t (map (lab (den W)) xs) e = true /\
                 le_ext (Some (U I W C t)) (get (map (lab (den W)) xs) O) = true.
  Proof.
    intros t r H. unfold check_type in H. cbv zeta in H.
    step H E0. destruct (rtrie r) as [[xs |] |]; [| discriminate | discriminate].
    step H E1. exists xs. unfold progress in H. revert H.
    destruct (tdefault C) as [| q |] eqn:Hd; cbn iota; intros H.
    - exists ENone. step H E2. step H E3. step H E4.
      apply negb_false_iff in E3, E4. simpl. auto.
    - destruct (node_labels I W (rexit r)) as [E |] eqn:E2; cbn iota in H; [| discriminate].
      exists (EConst E). step H E3. step H E4. step H E5.
      apply negb_false_iff in E3, E4, E5. simpl. split; [exists q; auto | auto].
    - destruct (Nat.eqb t (tgoal C)) eqn:Hs; cbn iota in H.
      + exists ESame. step H E2. step H E3. step H E4. apply Nat.eqb_eq in Hs.
        apply negb_false_iff in E3, E4. simpl. auto.
      + destruct (node_labels I W (rP r)) as [P |] eqn:E2; cbn iota in H; [| discriminate].
        destruct (node_labels I W (rQ r)) as [Q |] eqn:E3; cbn iota in H; [| discriminate].
        exists (EOther P Q). apply Nat.eqb_neq in Hs.
        step H E4. step H E5. step H E6.
        apply negb_false_iff in E4, E5, E6. repeat rewrite andb_true_iff in E4.
        destruct E4 as [[H1 H2] H3]. simpl. auto 10.
  Qed.

  (** ** The trie: its root, prefix closure, and the entries in it. *)
  Lemma fold_head : forall l x acc, exists rest, fold_left add_new l (x :: acc) = x :: rest.
  Proof.
    induction l as [| y l IH]; intros x acc; simpl; [exists acc; reflexivity |].
    unfold add_new at 2. destruct (memb y (x :: acc)); [apply IH |].
    simpl. apply IH.
  Qed.

  Lemma trie_root : index_of [start I] trie = Some O.
  Proof.
    unfold Kernel.trie. destruct (fold_head (flat_map (fun e => prefixes (fst e)) (tentries C)) [start I] [])
      as [rest ->]. simpl. rewrite Nat.eqb_refl. reflexivity.
  Qed.

  Lemma in_prefixes : forall x w, In x (prefixes w) <-> exists k, (2 <= k <= length w)%nat /\ x = firstn k w.
  Proof.
    intros x w. unfold prefixes. rewrite in_map_iff. split.
    - intros [k [<- Hk]]. apply in_seq in Hk. exists k. split; [lia | reflexivity].
    - intros [k [Hk ->]]. exists k. split; [reflexivity | apply in_seq; lia].
  Qed.

  Lemma firstn_snoc : forall (w : list nat) m, (m < length w)%nat -> firstn (S m) w = firstn m w ++ [nth m w O].
  Proof.
    induction w as [| x w IH]; intros m Hm; simpl in *; [lia |].
    destruct m as [| m]; [reflexivity |]. simpl. rewrite IH by lia. reflexivity.
  Qed.

  Lemma in_trie : forall p, In p trie <-> p = [start I] \/ exists e, In e (tentries C) /\ In p (prefixes (fst e)).
  Proof.
    intros p. unfold Kernel.trie. rewrite add_new_In, in_flat_map. simpl. split.
    - intros [[<- | []] | H]; [left; reflexivity | right; exact H].
    - intros [-> | H]; [left; left; reflexivity | right; exact H].
  Qed.

  Lemma entry_start : forall e, In e (tentries C) -> exists l, fst e = start I :: l /\ (1 <= length l)%nat.
  Proof.
    intros e He. destruct (tentries_ok I C Hrule es dflt gl Hcr e He) as [Hw _].
    destruct (walk_ok_false I _ Hw) as [l [Hl [Hlen _]]]. exists l. auto.
  Qed.

  Lemma trie_closed : forall p u, In (p ++ [u]) trie -> p <> [] -> In p trie.
  Proof.
    intros p u H Hp. apply in_trie in H as [Heq | [e [He Hin]]].
    - destruct p as [| x [| y p]]; [contradiction | discriminate | discriminate].
    - apply in_prefixes in Hin as [k [Hk Heq]].
      destruct k as [| k]; [lia |].
      rewrite firstn_snoc in Heq by lia. apply app_inj_tail in Heq as [-> _].
      apply in_trie. destruct (Nat.le_gt_cases 2 k) as [H2 | H2].
      + right. exists e. split; [exact He | apply in_prefixes; exists k; split; [lia | reflexivity]].
      + left. destruct (entry_start e He) as [l [Hl _]]. rewrite Hl.
        assert (k = 1%nat) by lia. subst k. reflexivity.
  Qed.

  Lemma lookup_in_trie : forall p q, lookup C p = Some q -> In p trie.
  Proof.
    intros p q H. destruct (lookup_entry C p q H) as [e [He [Hp _]]].
    apply in_trie. right. exists e. split; [exact He |]. apply in_prefixes.
    destruct (entry_start e He) as [l [Hl Hlen]]. exists (length (fst e)).
    split; [rewrite Hl; simpl; lia | rewrite firstn_all; symmetry; exact Hp].
  Qed.

  (** Off the trie σ is the default's distribution. *)
  Lemma off_trie_sigma : forall p u, p <> [] -> index_of p trie = None ->
    sigma I W C p u = match dflt with
                      | DNone => None
                      | DDist q => Some q
                      | DProgress => Some (map (fun i => if Nat.eqb i gl then prog I W C p u else 1 - prog I W C p u) (seq 0 2))
                      end.
  Proof.
    intros p u Hp Hn. unfold sigma.
    destruct (lookup C (p ++ [u])) as [q |] eqn:Hl.
    - exfalso. apply (index_of_none p trie Hn). apply (trie_closed p u); [exact (lookup_in_trie _ q Hl) | exact Hp].
    - unfold tdefault, tgoal. rewrite Hcr. reflexivity.
  Qed.

  (** ** Extended arithmetic. *)
  Lemma ole_refl : forall a, ole a a.
  Proof. intros [x |]; simpl; [lra | exact Logic.I]. Qed.

  Lemma ole_trans : forall a b c, ole a b -> ole b c -> ole a c.
  Proof. intros [x |] [y |] [z |]; simpl; intros; try lra; try contradiction; exact Logic.I. Qed.

  Lemma omin_le_left : forall a b, ole (omin a b) a.
  Proof.
    intros [x |] [y |]; simpl; try exact Logic.I; try lra.
    destruct (Qle_bool x y) eqn:E; [lra |].
    assert (Hn : ~ (x <= y)) by (intros Hc; apply Qle_bool_iff in Hc; congruence). apply Qnot_le_lt in Hn. lra.
  Qed.

  Lemma omin_le_right : forall a b, ole (omin a b) b.
  Proof.
    intros [x |] [y |]; simpl; try exact Logic.I; try lra.
    destruct (Qle_bool x y) eqn:E; [apply Qle_bool_iff; exact E | lra].
  Qed.

  Lemma ole_omin : forall a b c, ole a b -> ole a c -> ole a (omin b c).
  Proof.
    intros a [y |] [z |]; simpl; intros H1 H2; auto.
    destruct (Qle_bool y z); auto.
  Qed.

  Lemma ole_omin_mono : forall a a' b b', ole a a' -> ole b b' -> ole (omin a b) (omin a' b').
  Proof.
    intros a a' b b' H1 H2. apply ole_omin.
    - exact (ole_trans _ _ _ (omin_le_left a b) H1).
    - exact (ole_trans _ _ _ (omin_le_right a b) H2).
  Qed.

  Lemma oaddq_omin : forall w a b, ole (omin (oaddq w a) (oaddq w b)) (oaddq w (omin a b)).
  Proof.
    intros w [x |] [y |]; simpl; try lra; try exact Logic.I.
    destruct (Qle_bool x y) eqn:E; destruct (Qle_bool (w + x) (w + y)) eqn:E'; simpl; try lra.
    - assert (Hn : ~ (w + x <= w + y)) by (intros Hc; apply Qle_bool_iff in Hc; congruence).
      apply Qle_bool_iff in E. lra.
    - apply Qle_bool_iff in E'. exact E'.
  Qed.

  Definition phiO (p q : option Q) (c : Q) : option Q :=
    match q with Some y => omin p (Some (y - c)) | None => p end.

  Lemma phiO_left : forall p q c, ole (phiO p q c) p.
  Proof. intros p [y |] c; simpl; [apply omin_le_left | apply ole_refl]. Qed.

  Lemma other_keep : forall pv qv pu qu w c, ole pv (oaddq w pu) -> ole qv (oaddq w qu) ->
    ole (phiO pv qv c) (oaddq w (phiO pu qu c)).
  Proof.
    intros pv qv pu [y |] w c H1 H2; simpl.
    - destruct qv as [x |]; simpl in H2; [| contradiction].
      eapply ole_trans; [| apply oaddq_omin]. simpl. apply ole_omin_mono; [exact H1 | simpl; lra].
    - exact (ole_trans _ _ _ (phiO_left pv qv c) H1).
  Qed.

  Lemma other_drop : forall pv qv pu qu w c d, ole pv (oaddq w pu) -> ole qv (oaddq w qu) ->
    ole qu (oaddq d pu) -> ole (phiO pv qv c) (oaddq (w - c + d) (phiO pu qu d)).
  Proof.
    intros pv qv pu qu w c d H1 H2 H3. destruct qu as [y |].
    - destruct qv as [x |]; simpl in H2; [| contradiction].
      eapply ole_trans; [| apply oaddq_omin]. simpl.
      eapply ole_trans; [apply omin_le_right |]. apply ole_omin.
      + destruct pu as [z |]; simpl in *; [lra | exact Logic.I].
      + simpl. lra.
    - destruct pu as [z |]; simpl in H3; [contradiction |]. simpl.
      destruct (phiO pv qv c); exact Logic.I.
  Qed.

  (** ** The prefix graph of type [t] and its potential. *)
  Section OneType.
    Variable t : nat.
    Hypothesis Ht : (t < N I)%nat.
    Variable xs : list (option BinNums.Z).
    Variable e : exitp.
    Hypothesis He : exit_spec t e.
    Hypothesis Htrie : trie_ok I W C t (map (lab (den W)) xs) e = true.
    Notation phi := (map (lab (den W)) xs).

    Definition Phi (p : list nat) : option Q :=
      match index_of p trie with Some i => get phi i | None => exit_phi e (last p O) (cmin W C p) end.

    Definition parc (p p' : list nat) : Prop :=
      exists v, p' = p ++ [v] /\ has_arc I (last p O) v = true /\ alive I W v = true.
    Definition pcost (p p' : list nat) : Q := wt I (last p O) (last p' O) * gsig p (last p' O) t.
    Definition pgoal (p : list nat) : Prop := isgoal I (last p O) = true.
    Definition pterm (p : list nat) : Q := Dv W t (last p O).
    Definition Rp (p : list nat) : Prop :=
      (exists l, p = start I :: l) /\ alive I W (last p O) = true /\ (last p O < n I)%nat /\
      (tdefault C = DNone -> In p trie).

    Lemma trie_ok_at : forall p i, index_of p trie = Some i -> alive I W (last p O) = true ->
      (isgoal I (last p O) = true -> le_ext (get phi i) (D t (last p O)) = true) /\
      (isgoal I (last p O) = false -> forall u w, In (u, w) (arcs I (last p O)) -> alive I W u = true ->
         exists q, sigma I W C p u = Some q /\
           match index_of (p ++ [u]) trie with
           | Some j => le_ext (get phi i) (oadd (w * sig_t I W C p u t) (get phi j)) = true
           | None => e <> ENone /\
                     le_ext (get phi i) (oadd (w * sig_t I W C p u t)
                       (exit_phi e u (if progress C then omin (cmin W C p) (D (tgoal C) u) else cmin W C p))) = true
           end).
    Proof.
      intros p i Hi' Ha. destruct (index_of_nth p trie i Hi') as [Hnth Hlt].
      unfold trie_ok in Htrie. rewrite forallb_forall in Htrie.
      specialize (Htrie i (proj2 (in_seq _ _ _) (conj (Nat.le_0_l i) Hlt))).
      rewrite Hnth, Ha in Htrie. simpl in Htrie. split.
      - intros Hg. rewrite Hg in Htrie. exact Htrie.
      - intros Hg u w Hin Hu. rewrite Hg in Htrie. rewrite forallb_forall in Htrie.
        specialize (Htrie (u, w) Hin). simpl in Htrie. rewrite Hu in Htrie. simpl in Htrie.
        destruct (sigma I W C p u) as [q |]; [| discriminate]. exists q. split; [reflexivity |].
        destruct (index_of (p ++ [u]) trie) as [j |]; [exact Htrie |].
        destruct e; [discriminate | | |]; (split; [discriminate | exact Htrie]).
    Qed.

    Lemma oadd_oaddq : forall x b, oadd x b = oaddq x b.
    Proof. intros x [y |]; reflexivity. Qed.

    Lemma ole_oaddq_eq : forall a x y b, x == y -> ole a (oaddq x b) -> ole a (oaddq y b).
    Proof. intros [z |] x y [u |]; simpl; intros Hxy H; auto; lra. Qed.

    Lemma exit_other : forall P Q x c, exit_phi (EOther P Q) x (Some c) = phiO (get P x) (get Q x) c.
    Proof. intros P Q x c. simpl. destruct (get Q x); reflexivity. Qed.

    Lemma not_pgoal : forall p, ~ pgoal p -> isgoal I (last p O) = false.
    Proof. intros p H. unfold pgoal in H. destruct (isgoal I (last p O)); [contradiction | reflexivity]. Qed.

    Lemma tdefault_dflt : tdefault C = dflt.
    Proof. unfold tdefault. rewrite Hcr. reflexivity. Qed.
    Lemma tgoal_gl : tgoal C = gl.
    Proof. unfold tgoal. rewrite Hcr. reflexivity. Qed.

    Lemma nth_map2 : forall (f : nat -> Q) t', (t' < 2)%nat -> nth t' (map f (seq 0 2)) 0 = f t'.
    Proof. intros f [| [| t']] H; [reflexivity | reflexivity | lia]. Qed.

    Lemma progress_N : tdefault C = DProgress -> N I = 2%nat.
    Proof.
      intros H. pose proof Hrule as Hr. unfold rule_ok in Hr. rewrite Hcr in Hr.
      rewrite tdefault_dflt in H. subst dflt. apply Hr.
    Qed.

    Lemma Rp_closed : forall p p', Rp p -> ~ pgoal p -> parc p p' -> Rp p'.
    Proof.
      intros p p' [[l Hl] [Ha [Hn Hd]]] Hng [u [-> [Hu Hau]]].
      split; [exists (l ++ [u]); rewrite Hl; reflexivity |].
      rewrite last_app1. split; [exact Hau | split; [exact (arc_tgt I Hi _ _ Hu) |]].
      intros HD. specialize (Hd HD).
      destruct (index_of_In p trie Hd) as [i Hi'].
      destruct (trie_ok_at p i Hi' Ha) as [_ Harc].
      destruct (Harc (not_pgoal p Hng) u (wt I (last p O) u) (has_arc_wt I _ _ Hu) Hau) as [q [Hs _]].
      unfold sigma in Hs. destruct (lookup C (p ++ [u])) as [q' |] eqn:Hl'.
      - exact (lookup_in_trie _ _ Hl').
      - rewrite HD in Hs. discriminate.
    Qed.

    Lemma exit_other_le : forall P Q x c, ole (exit_phi (EOther P Q) x c) (get P x).
    Proof.
      intros P Q x c. simpl. destruct (get Q x), c; try apply ole_refl. apply omin_le_left.
    Qed.

    Theorem Phi_feasible : feasible_ext (list nat) parc pcost pgoal pterm Rp Phi.
    Proof.
      split.
      - intros p [[l Hl] [Ha [Hn Hd]]] Hg. unfold pgoal in Hg. unfold Phi, pterm.
        destruct (reach_at I W Hreach t (last p O) Ht (or_intror (isgoal_In I _ Hg))) as [x Hx].
        rewrite (Dv_some W t _ x Hx).
        destruct (index_of p trie) as [i |] eqn:Hi'.
        + destruct (trie_ok_at p i Hi' Ha) as [Hgoal _]. specialize (Hgoal Hg).
          rewrite Hx in Hgoal. apply le_ext_ole. exact Hgoal.
        + destruct e as [| E | | P Q]; simpl in He.
          * exfalso. apply (index_of_none p trie Hi'). apply Hd. exact He.
          * destruct He as [q [Hq Harc]]. unfold arcs_ok in Harc. apply andb_true_iff in Harc as [_ Hgs].
            simpl in Hgs. rewrite forallb_forall in Hgs. specialize (Hgs _ (isgoal_In I _ Hg)).
            rewrite Hx in Hgs. apply le_ext_ole. exact Hgs.
          * destruct He as [_ Hs]. simpl. rewrite Hs in Hx.
            assert (Hp : p <> []) by (rewrite Hl; discriminate).
            destruct (cmin_le_last W C p x Hp Hx) as [c [Hc Hle]]. rewrite Hc. simpl. exact Hle.
          * destruct He as [_ [_ [HP _]]]. unfold arcs_ok in HP. apply andb_true_iff in HP as [_ Hgs].
            simpl in Hgs. rewrite forallb_forall in Hgs. specialize (Hgs _ (isgoal_In I _ Hg)).
            rewrite Hx in Hgs. apply le_ext_ole in Hgs.
            exact (ole_trans _ _ _ (exit_other_le P Q _ _) Hgs).
      - intros p p' [[l Hl] [Ha [Hn Hd]]] Hng [u [-> [Hu Hau]]].
        pose proof (not_pgoal p Hng) as Hg. unfold Phi, pcost. rewrite last_app1.
        set (v := last p O) in *.
        pose proof (has_arc_wt I v u Hu) as Hin. pose proof (wt_pos I Hi v u Hu) as Hw.
        set (w := wt I v u) in *.
        assert (Hp : p <> []) by (rewrite Hl; discriminate).
        destruct (index_of p trie) as [i |] eqn:Hi'.
        + destruct (trie_ok_at p i Hi' Ha) as [_ Harc].
          destruct (Harc Hg u w Hin Hau) as [q [Hs Hnext]].
          rewrite (gsig_defined I W C p u t q Hs).
          destruct (index_of (p ++ [u]) trie) as [j |].
          * apply le_ext_ole in Hnext. rewrite oadd_oaddq in Hnext. exact Hnext.
          * destruct Hnext as [Hne Hnext]. apply le_ext_ole in Hnext. rewrite oadd_oaddq in Hnext.
            rewrite cmin_app1.
            destruct (progress C) eqn:Hpr; [exact Hnext |].
            destruct e as [| E | | P Q]; [contradiction | exact Hnext | |]; simpl in He;
              unfold progress in Hpr; destruct He as [HD _]; rewrite HD in Hpr; discriminate.
        + assert (Hsig := off_trie_sigma p u Hp Hi').
          assert (Hi2 : index_of (p ++ [u]) trie = None).
          { destruct (index_of (p ++ [u]) trie) as [j |] eqn:E2; [exfalso | reflexivity].
            destruct (index_of_nth _ _ _ E2) as [Hj Hjl].
            apply (index_of_none p trie Hi'). apply (trie_closed p u); [| exact Hp].
            rewrite <- Hj. apply nth_In. exact Hjl. }
          rewrite Hi2.
          destruct (cmin_start I W C Hreach Hrule es dflt gl Hcr l) as [c Hc]. rewrite <- Hl in Hc.
          destruct e as [| E | | P Q]; simpl in He.
          * exfalso. apply (index_of_none p trie Hi'). apply Hd. exact He.
          * destruct He as [q [Hq Harc]]. rewrite tdefault_dflt in Hq. rewrite Hq in Hsig.
            unfold gsig. rewrite Hsig. simpl.
            unfold arcs_ok in Harc. apply andb_true_iff in Harc as [Harc _].
            rewrite forallb_forall in Harc.
            specialize (Harc v (proj2 (in_seq _ _ _) (conj (Nat.le_0_l v) Hn))).
            rewrite Hg in Harc. simpl in Harc. rewrite forallb_forall in Harc.
            specialize (Harc (u, w) Hin). apply le_ext_ole in Harc. rewrite oadd_oaddq in Harc.
            simpl in Harc. eapply ole_oaddq_eq; [| exact Harc]. ring.
          * destruct He as [HD Hs]. pose proof (progress_N HD) as HN2.
            rewrite tdefault_dflt in HD. rewrite HD in Hsig.
            unfold gsig. rewrite Hsig. simpl exit_phi. rewrite cmin_app1, Hc.
            rewrite nth_map2 by lia.
            replace (t =? gl) with true by (symmetry; apply Nat.eqb_eq; rewrite <- tgoal_gl; exact Hs).
            unfold prog. rewrite Hc. fold v. fold w. rewrite <- Hs.
            destruct (D t u) as [d |]; simpl.
            -- destruct (Qle_bool c d) eqn:Hcd; simpl; rewrite ?Hcd; [lra |].
               setoid_replace (w * ((c - d) / w) + d) with c by (field; lra). lra.
            -- lra.
          * destruct He as [HD [Hs [HP [HQ H4]]]]. pose proof (progress_N HD) as HN2.
            rewrite tdefault_dflt in HD. rewrite HD in Hsig.
            assert (Hgl : (gl < 2)%nat) by (rewrite <- HN2, <- tgoal_gl; exact (tgoal_lt I C Hrule es dflt gl Hcr)).
            unfold gsig. rewrite Hsig. rewrite nth_map2 by lia.
            rewrite tgoal_gl in Hs. apply Nat.eqb_neq in Hs. rewrite Hs.
            rewrite cmin_app1, Hc.
            (* the labels' inequalities at v and u *)
            unfold arcs_ok in HP, HQ. apply andb_true_iff in HP as [HP _]. apply andb_true_iff in HQ as [HQ _].
            rewrite forallb_forall in HP, HQ.
            assert (Hv : In v (seq 0 (n I))) by (apply in_seq; lia).
            specialize (HP v Hv). specialize (HQ v Hv). rewrite Hg in HP, HQ. simpl in HP, HQ.
            rewrite forallb_forall in HP, HQ. specialize (HP (u, w) Hin). specialize (HQ (u, w) Hin).
            apply le_ext_ole in HP, HQ. rewrite oadd_oaddq in HP, HQ. simpl in HP, HQ.
            apply (ole_oaddq_eq _ (1 * w) w) in HP; [| ring]. apply (ole_oaddq_eq _ (1 * w) w) in HQ; [| ring].
            rewrite forallb_forall in H4.
            assert (Hu' : In u (seq 0 (n I))) by (apply in_seq; pose proof (arc_tgt I Hi v u Hu); lia).
            specialize (H4 u Hu'). rewrite Hau in H4. simpl in H4. apply le_ext_ole in H4.
            rewrite exit_other. unfold prog. rewrite Hc. fold v. fold w. revert H4.
            destruct (D (tgoal C) u) as [d |] eqn:Hdu; simpl; intros H4.
            -- rewrite oadd_oaddq in H4. destruct (Qle_bool c d) eqn:Hcd; simpl; rewrite ?Hcd.
               ++ eapply ole_oaddq_eq; [| exact (other_keep (get P v) (get Q v) (get P u) (get Q u) w c HP HQ)]. ring.
               ++ eapply ole_oaddq_eq; [| exact (other_drop (get P v) (get Q v) (get P u) (get Q u) w c d HP HQ H4)].
                  field. lra.
            -- eapply ole_oaddq_eq; [| exact (other_keep (get P v) (get Q v) (get P u) (get Q u) w c HP HQ)]. ring.
    Qed.

    (** ** Game walks lifted to the prefix graph. *)
    Fixpoint lift (p : list nat) (l : list nat) : list (list nat) :=
      match l with [] => [] | v :: l' => (p ++ [v]) :: lift (p ++ [v]) l' end.

    Lemma lift_swalk : forall l p, gwalk nat (fun a b => has_arc I a b = true) (isgoal I) (last p O) l ->
      (forall x, In x l -> alive I W x = true) -> swalk (list nat) parc pgoal p (lift p l).
    Proof.
      induction l as [| v l IH]; intros p Hw Ha; cbn [lift swalk gwalk] in *.
      - exact Hw.
      - destruct Hw as [Hng [Huv Hw]]. split; [unfold pgoal; congruence |]. split.
        + exists v. split; [reflexivity | split; [exact Huv | apply Ha; left; reflexivity]].
        + apply IH; [rewrite last_app1; exact Hw | intros x Hx; apply Ha; right; exact Hx].
    Qed.

    Lemma lift_cost : forall l h u, scost (list nat) pcost pterm (rev (u :: h)) (lift (rev (u :: h)) l) ==
      J nat nat (wt I) (Dv W) t (defender I W C) h u l.
    Proof.
      induction l as [| v l IH]; intros h u.
      - cbn [lift scost J]. unfold pterm. rewrite last_rev_cons. reflexivity.
      - cbn [lift scost J]. change (rev (u :: h) ++ [v]) with (rev (v :: u :: h)).
        rewrite IH. unfold pcost, defender. rewrite !last_rev_cons. reflexivity.
    Qed.

    (** Every game walk costs type [t] at least U_t. *)
    Theorem attacker_bound : le_ext (Some (U I W C t)) (get phi O) = true ->
      forall l, gwalk nat (fun a b => has_arc I a b = true) (isgoal I) (start I) l ->
      U I W C t <= J nat nat (wt I) (Dv W) t (defender I W C) [] (start I) l.
    Proof.
      intros HU l Hw.
      destruct (inst_facts I Hi) as [_ [_ [Hs0 _]]].
      pose proof (gwalk_all_alive I W Hi Hdist l (start I) Hw Hs0) as Hal.
      assert (HR : Rp [start I]).
      { split; [exists []; reflexivity |]. simpl.
        split; [apply (Hal (start I) (or_introl eq_refl)) | split; [exact Hs0 |]].
        intros _. apply in_trie. left; reflexivity. }
      destruct (potential_bound_ext (list nat) parc pcost pgoal pterm Rp Rp_closed Phi Phi_feasible
                  (lift [start I] l) [start I] HR
                  (lift_swalk l [start I] Hw (fun x Hx => proj1 (Hal x (or_intror Hx))))) as [x [Hx Hle]].
      unfold Phi in Hx. rewrite trie_root in Hx. rewrite Hx in HU. apply le_ext_ole in HU. simpl in HU.
      pose proof (lift_cost l [] (start I)) as Hc. simpl rev in Hc. lra.
    Qed.
  End OneType.
End Attacker.
