(** * The kernel's acceptance condition, as an executable function.

    [decide] mirrors [dppverify/kernel/check.py] ([_decide]) step by step,
    after the reading of the three JSON documents (the untrusted glue of the
    extracted checker: node ids become indices, numbers become rationals,
    structural defects of a document are refused there with the Python
    kernel's status).  Each check below names the Python function it mirrors
    and the item of proofs/KERNEL.md it decides.  Labels of the witness are
    integers over its denominator [S] ([None] is +∞).  [KernelSound.v] proves
    that [decide = Pass] implies a weak PBNE of the untruncated game. *)

From Coq Require Import QArith List Bool Arith ZArith.
Import ListNotations.
From DPP Require Import Sums Distances.
Open Scope Q_scope.

Inductive verdict := Pass | Refuted | BadInput | Undecided.

(** ** The documents, after reading. *)
Record instance := mkInstance {
  adj : list (list (nat * Q));       (* adj[v]: the arcs (u, w) of v, targets in increasing order *)
  start : nat;
  goals : list nat;                  (* the goals, in the instance's order: type j has goal j *)
  prior : list Q }.

(** A table Defender's default. *)
Inductive default := DNone | DDist (q : list Q) | DProgress.

(** The Defender as the profile states it. *)
Inductive rule :=
  | RTable (entries : list (list nat * list Q)) (dflt : default) (goal : nat)
  | RGuarantee (h : list Q) (extras : list (list nat)).  (* the guarantee rule: h, extra normals *)

(** [dpp-ngoal-profile/1]: [ngoals] the optional "goals" list, one mixture per
    type (walk, probability), the rule. *)
Record ngprofile := mkNg { ngoals : option (list nat); nmix : list (list (list nat * Q)); nrule : rule }.

(** [dpp-profile/1]: the primary and secondary goals (nodes), their mixtures,
    the rule's goal (a node), "progress" or a table (probability on the
    rule's goal per entry; default none, "progress" or a probability). *)
Inductive default2 := D2None | D2Progress | D2Prob (p : Q).
Inductive rule2 := R2Progress | R2Table (entries : list (list nat * Q)) (dflt : default2) | R2Other.
Record tgprofile := mkTg { tprimary : nat; tsecondary : nat; tmix_primary : list (list nat * Q);
                           tmix_secondary : list (list nat * Q); trgoal : nat; trule : rule2 }.

Inductive profile := PN (p : ngprofile) | P2 (p : tgprofile).

(** A witness list: [None] when the key is absent, [Some None] when its value
    is not a list of integers or null, else the labels. *)
Definition labels := option (option (list (option Z))).

Record typerec := mkType { rec_ok : bool;  (* a JSON object with no other keys than these *)
                           rtrie : labels; rexit : labels; rP : labels; rQ : labels }.

(** The guarantee rule's witness: per normal its labels m_a(v), the covers,
    and per prefix of the profile's walks σ and one dual (y, fix, z) per
    stage.  [NBad]: not a list; [NList]: the entries, [None] where not a number. *)
Inductive nums := NBad | NList (l : list (option Q)).
Record dualrec := mkDual { dy : nums; dfix : nums; dz : option Q }.
Record steprec := mkStep { ssigma : nums; sduals : option (list dualrec) }.
Record gwit := mkGwit { gm : list (option (list (option Z))); gcovers : list nums;
                        gsteps : option (list steprec) }.

Record witness := mkWitness {
  denominator : Z;
  distances : option (list (list (option Z)));    (* None: not N lists of n integers or null *)
  counterexamples : list (nat * list nat);
  wtypes : option (list typerec);
  has_types : bool; has_counterexamples : bool;   (* which keys the witness has *)
  wguarantee : option (option gwit) }.            (* absent / not the right shape / the record *)

(** ** Small helpers. *)
Fixpoint leqb (a b : list nat) : bool :=
  match a, b with
  | [], [] => true
  | x :: a', y :: b' => Nat.eqb x y && leqb a' b'
  | _, _ => false
  end.

Definition memb (p : list nat) (l : list (list nat)) : bool := existsb (leqb p) l.

Fixpoint index_of (p : list nat) (l : list (list nat)) : option nat :=
  match l with
  | [] => None
  | x :: l' => if leqb p x then Some 0%nat else option_map S (index_of p l')
  end.

Fixpoint nodupb (l : list (list nat)) : bool :=
  match l with [] => true | x :: l' => negb (memb x l') && nodupb l' end.

Definition qsum (l : list Q) : Q := fold_right Qplus 0 l.
Definition qmax2 (x y : Q) : Q := if Qle_bool x y then y else x.
Definition qmax (l : list Q) : Q := fold_right qmax2 0 l.
Definition ltb (x y : Q) : bool := negb (Qle_bool y x).

(** The order of +∞-extended rationals: [None] is +∞. *)
Definition le_ext (a b : option Q) : bool :=
  match a, b with
  | _, None => true
  | Some x, Some y => Qle_bool x y
  | None, Some _ => false
  end.

Definition oadd (x : Q) (b : option Q) : option Q := oplus x b.
Definition osub (b : option Q) (x : Q) : option Q := match b with Some y => Some (y - x) | None => None end.

Definition lab (S : Z) (x : option Z) : option Q :=
  match x with Some z => Some (inject_Z z / inject_Z S) | None => None end.

Section Kernel.
  Variable I : instance.

  Definition n : nat := length (adj I).
  Definition arcs (v : nat) : list (nat * Q) := nth v (adj I) [].
  Definition N : nat := length (goals I).
  Definition types : list nat := seq O N.
  Definition goal (j : nat) : nat := nth j (goals I) O.
  Definition isgoal (v : nat) : bool := existsb (Nat.eqb v) (goals I).
  Definition priorq (t : nat) : Q := nth t (prior I) 0.
  Definition has_arc (v u : nat) : bool := existsb (fun a => Nat.eqb (fst a) u) (arcs v).
  Definition wt (v u : nat) : Q :=
    match find (fun a => Nat.eqb (fst a) u) (arcs v) with Some a => snd a | None => 0 end.

  (** The reader's conditions on the instance ([reading.read_instance]):
      positive weights, arcs between nodes, 2 to 64 distinct goals, a prior in
      (0, 1) per goal summing to 1. *)
  Definition instance_ok : bool :=
    forallb (fun row => forallb (fun a => Nat.ltb (fst a) n && ltb 0 (snd a)) row) (adj I) &&
    Nat.ltb (start I) n && forallb (fun g => Nat.ltb g n) (goals I) &&
    Nat.leb 2%nat N && Nat.leb N 64%nat && nodupb (map (fun g => [g]) (goals I)) &&
    Nat.eqb (length (prior I)) N && forallb (fun b => ltb 0 b && ltb b 1) (prior I) &&
    Qeq_bool (qsum (prior I)) 1.

  (** ** Walks ([profile.walk]). *)
  Fixpoint steps_ok (u : nat) (l : list nat) : bool :=
    match l with
    | [] => true
    | v :: l' => negb (isgoal u) && has_arc u v && steps_ok v l'
    end.

  Definition walk_ok (complete : bool) (w : list nat) : bool :=
    match w with
    | [] => false
    | s :: l => forallb (fun x => Nat.ltb x n) w && Nat.eqb s (start I) && steps_ok s l &&
                (if complete then isgoal (last w O) else Nat.leb 2%nat (length w))
    end.

  (** [profile._mixture]: a non-empty list of distinct walks of the game,
      probabilities >= 0 summing to 1. *)
  Definition mixture_ok (m : list (list nat * Q)) : bool :=
    negb (Nat.eqb (length m) O) && forallb (fun e => Qle_bool 0 (snd e) && walk_ok true (fst e)) m &&
    nodupb (map fst m) && Qeq_bool (qsum (map snd m)) 1.

  (** [profile._distribution]: N probabilities in [0, 1] summing to 1. *)
  Definition dist_ok (q : list Q) : bool :=
    Nat.eqb (length q) N && forallb (fun x => Qle_bool 0 x && Qle_bool x 1) q && Qeq_bool (qsum q) 1.

  Definition entries_ok (es : list (list nat * list Q)) : bool :=
    forallb (fun e => walk_ok false (fst e) && dist_ok (snd e)) es && nodupb (map fst es).

  (** The profile in canonical form: one mixture per type (goal order) and the rule. *)
  Record canon := mkCanon { mix : list (list (list nat * Q)); crule : rule }.

  Definition two (j : nat) (p : Q) : list Q := if Nat.eqb j O then [p; 1 - p] else [1 - p; p].
  Definition prob_ok (p : Q) : bool := Qle_bool 0 p && Qle_bool p 1.

  Fixpoint find_index (g : nat) (l : list nat) : option nat :=
    match l with [] => None | x :: l' => if Nat.eqb x g then Some 0%nat else option_map S (find_index g l') end.

  (** [profile.read_profile], its semantic checks (refuted when they fail). *)
  Definition read_profile (P : profile) : option canon :=
    match P with
    | PN p =>
        if (match ngoals p with Some gs => negb (leqb gs (goals I)) | None => false end) then None else
        if negb (Nat.eqb (length (nmix p)) N) || negb (forallb mixture_ok (nmix p)) then None else
        match nrule p with
        | RTable es d _ =>
            if negb (entries_ok es) then None else
            match d with
            | DNone => Some (mkCanon (nmix p) (RTable es DNone O))
            | DDist q => if dist_ok q then Some (mkCanon (nmix p) (RTable es (DDist q) O)) else None
            | DProgress => None
            end
        | RGuarantee h ex =>
            if Nat.eqb (length h) N && forallb (fun a => Nat.eqb (length a) N) ex
            then Some (mkCanon (nmix p) (RGuarantee h ex)) else None
        end
    | P2 p =>
        match find_index (tprimary p) (goals I), find_index (tsecondary p) (goals I) with
        | Some first, Some second =>
            if Nat.eqb first second || negb (Nat.eqb N 2%nat) then None else
            if ltb (priorq first) (priorq (1 - first)%nat) then None else
            if negb (mixture_ok (tmix_primary p) && mixture_ok (tmix_secondary p)) then None else
            let mixes := if Nat.eqb first 0 then [tmix_primary p; tmix_secondary p]
                         else [tmix_secondary p; tmix_primary p] in
            match find_index (trgoal p) (goals I) with
            | None => None
            | Some j =>
                match trule p with
                | R2Other => None
                | R2Progress => Some (mkCanon mixes (RTable [] DProgress j))
                | R2Table es d =>
                    if negb (forallb (fun e => walk_ok false (fst e) && prob_ok (snd e)) es &&
                             nodupb (map fst es)) then None else
                    let es' := map (fun e => (fst e, two j (snd e))) es in
                    match d with
                    | D2None => Some (mkCanon mixes (RTable es' DNone j))
                    | D2Progress => Some (mkCanon mixes (RTable es' DProgress j))
                    | D2Prob q => if prob_ok q then Some (mkCanon mixes (RTable es' (DDist (two j q)) j)) else None
                    end
                end
            end
        | _, _ => None
        end
    end.

  (** ** The witness's distances ([check._check_distances]: K.1; (R)). *)
  Variable W : witness.
  Definition den : Z := denominator W.
  Definition dlists : list (list (option Z)) := match distances W with Some l => l | None => [] end.
  Definition D (j v : nat) : option Q := lab den (nth v (nth j dlists []) None).
  Definition Dv (j v : nat) : Q := match D j v with Some x => x | None => 0 end.

  Definition dist_shape_ok : bool :=
    match distances W with
    | Some l => Nat.eqb (length l) N && forallb (fun xs => Nat.eqb (length xs) n) l
    | None => false
    end.

  Definition distances_ok : bool := forallb (fun j => bellman_ok (adj I) (goal j) (D j)) types.

  Definition reach_ok : bool :=
    forallb (fun j => forallb (fun v => match D j v with Some _ => true | None => false end)
                                (start I :: goals I)) types.

  Definition alive (v : nat) : bool := existsb (fun j => match D j v with Some _ => true | None => false end) types.

  (** ** The table Defender ([table.TableRule]). *)
  Variable C : canon.
  Definition tentries : list (list nat * list Q) :=
    match crule C with RTable es _ _ => es | RGuarantee _ _ => [] end.
  Definition tdefault : default := match crule C with RTable _ d _ => d | RGuarantee _ _ => DNone end.
  Definition tgoal : nat := match crule C with RTable _ _ g => g | RGuarantee _ _ => O end.
  Definition progress : bool := match tdefault with DProgress => true | _ => false end.

  Definition lookup (p : list nat) : option (list Q) :=
    option_map snd (find (fun e => leqb (fst e) p) tentries).

  (** The trie: the prefix closure of the entries, canonically numbered (the
      start is 0, then each entry's prefixes in order, a prefix taking the
      next number when first met). *)
  Definition prefixes (w : list nat) : list (list nat) := map (fun k => firstn k w) (seq 2 (length w - 1)%nat).
  Definition add_new (acc : list (list nat)) (p : list nat) : list (list nat) :=
    if memb p acc then acc else acc ++ [p].
  Definition trie : list (list nat) :=
    fold_left add_new (flat_map (fun e => prefixes (fst e)) tentries) [[start I]].

  (** The running minimum of the progress goal's distance along a prefix. *)
  Definition cmin (p : list nat) : option Q := fold_left (fun c x => omin c (D tgoal x)) p None.

  (** The progress default's probability on its goal at the step [p -> v]:
      (c - c') / w with c' = min(c, d(v, g)). *)
  Definition prog (p : list nat) (v : nat) : Q :=
    match cmin p, D tgoal v with
    | Some c, Some d => if Qle_bool c d then 0 else (c - d) / wt (last p O) v
    | _, _ => 0
    end.

  (** σ at the prefix [p ++ [v]] ([TableRule.step]): the entry if listed,
      else the default's distribution; [None] where the table is undefined. *)
  Definition sigma (p : list nat) (v : nat) : option (list Q) :=
    match lookup (p ++ [v]) with
    | Some q => Some q
    | None => match tdefault with
              | DNone => None
              | DDist q => Some q
              | DProgress => Some (map (fun i => if Nat.eqb i tgoal then prog p v else 1 - prog p v) (seq O 2%nat))
              end
    end.

  Definition sig_t (p : list nat) (v : nat) (t : nat) : Q :=
    match sigma p v with Some q => nth t q 0 | None => 0 end.

  (** ** The profile's costs ([check._evaluate]): σ defined along every walk,
      and each type's cost [J_t(w)]. *)
  Fixpoint defined_along (p : list nat) (l : list nat) : bool :=
    match l with
    | [] => true
    | v :: l' => match sigma p v with Some _ => defined_along (p ++ [v]) l' | None => false end
    end.

  Fixpoint wcost (t : nat) (p : list nat) (l : list nat) : Q :=
    match l with
    | [] => Dv t (last p O)
    | v :: l' => wt (last p O) v * sig_t p v t + wcost t (p ++ [v]) l'
    end.

  Definition walk_defined (w : list nat) : bool := defined_along (firstn 1%nat w) (tl w).
  Definition walk_cost (t : nat) (w : list nat) : Q := wcost t (firstn 1%nat w) (tl w).

  Definition U (t : nat) : Q := qsum (map (fun e => snd e * walk_cost t (fst e)) (nth t (mix C) [])).

  (** ** The Defender's check ([defender.check_greedy], K.2 item 6): greedy on
      the Bayes masses at every reached prefix of the profile's walks. *)
  Definition all_walks : list (list nat) := flat_map (fun m => map fst m) (mix C).
  Definition mass_trie : list (list nat) :=
    fold_left add_new (flat_map prefixes all_walks) [].

  Definition is_prefix (p w : list nat) : bool := leqb p (firstn (length p) w).

  Definition mass (t : nat) (p : list nat) : Q :=
    priorq t * qsum (map (fun e => if is_prefix p (fst e) then snd e else 0) (nth t (mix C) [])).

  Definition greedy_at (p : list nat) : bool :=
    let ms := map (fun t => mass t p) types in
    let top := qmax ms in
    forallb (fun i => negb (ltb 0 top && ltb 0 (sig_t (removelast p) (last p O) i) && ltb (mass i p) top)) types.

  Definition greedy_ok : bool := forallb greedy_at mass_trie.

  (** ** The Attacker's checks of one type ([TableRule.check_type], K.2 item 5). *)
  Definition get (l : list (option Q)) (i : nat) : option Q := nth i l None.

  (** [TableRule.labels]: a per-node list, +∞ at dead nodes. *)
  Definition node_labels (x : labels) : option (list (option Q)) :=
    match x with
    | Some (Some xs) => if Nat.eqb (length xs) n
                        then Some (map (fun v => if alive v then lab den (nth v xs None) else None) (seq O n))
                        else None
    | _ => None
    end.

  (** [TableRule._arcs]: X(x) <= k·w + Y(u) on every arc of every non-goal
      node, and X(g) <= D_t(g) at the goals when asked. *)
  Definition arcs_ok (t : nat) (X Y : list (option Q)) (k : Q) (at_goals : bool) : bool :=
    forallb (fun v => isgoal v || forallb (fun a => le_ext (get X v) (oadd (k * snd a) (get Y (fst a)))) (arcs v))
            (seq O n) &&
    (negb at_goals || forallb (fun g => le_ext (get X g) (D t g)) (goals I)).

  Definition key_set (r : typerec) : list bool :=
    map (fun x => match x with Some _ => true | None => false end) [rtrie r; rexit r; rP r; rQ r].

  (** The exit potential: φ(u, c') after leaving the trie. *)
  Inductive exitp := ENone | EConst (E : list (option Q)) | ESame | EOther (P Q : list (option Q)).

  Definition exit_phi (e : exitp) (u : nat) (c2 : option Q) : option Q :=
    match e with
    | ENone => None
    | EConst E => get E u
    | ESame => c2
    | EOther P Q => match get Q u, c2 with
                    | Some q, Some c => omin (get P u) (Some (q - c))
                    | _, _ => get P u
                    end
    end.

  (** The trie's inequalities: at every alive trie prefix, φ ≤ terminal cost
      at a goal, else φ(p) ≤ w·σ(t) + φ(next) on every live arc. *)
  Definition trie_ok (t : nat) (phi : list (option Q)) (e : exitp) : bool :=
    forallb (fun i =>
      let p := nth i trie [] in
      let v := last p O in
      if negb (alive v) then true else
      if isgoal v then le_ext (get phi i) (D t v) else
      forallb (fun a =>
        let u := fst a in
        if negb (alive u) then true else
        let c2 := if progress then omin (cmin p) (D tgoal u) else cmin p in
        match sigma p u, index_of (p ++ [u]) trie with
        | None, _ => false
        | Some _, None => match e with ENone => false | _ => le_ext (get phi i) (oadd (snd a * sig_t p u t) (exit_phi e u c2)) end
        | Some _, Some j => le_ext (get phi i) (oadd (snd a * sig_t p u t) (get phi j))
        end) (arcs v))
    (seq O (length trie)).

  Definition check_type (t : nat) (r : typerec) : option verdict :=
    let same := Nat.eqb t tgoal in
    let keys := if progress then (if same then [true; false; false; false] else [true; false; true; true])
                else match tdefault with DNone => [true; false; false; false] | _ => [true; true; false; false] end in
    if negb (rec_ok r) || negb (forallb (fun b => b) (map (fun x => Bool.eqb (fst x) (snd x)) (combine (key_set r) keys)))
    then Some BadInput else
    match rtrie r with
    | Some (Some xs) =>
        if negb (Nat.eqb (length xs) (length trie)) then Some BadInput else
        let phi := map (lab den) xs in
        let exit :=
          if progress then
            (if same then Some ESame else
             match node_labels (rP r), node_labels (rQ r) with
             | Some P, Some Q => Some (EOther P Q)
             | _, _ => None
             end)
          else match tdefault with
               | DDist q => match node_labels (rexit r) with Some E => Some (EConst E) | None => None end
               | _ => Some ENone
               end in
        match exit with
        | None => Some BadInput
        | Some e =>
            let labels_ok :=
              match e with
              | EOther P Q =>
                  arcs_ok t P P 1 true && arcs_ok t Q Q 1 false &&
                  forallb (fun u => negb (alive u) || le_ext (get Q u) (match D tgoal u with
                                                                  | Some d => oadd d (get P u)
                                                                  | None => None end)) (seq O n)
              | EConst E => arcs_ok t E E (match tdefault with DDist q => nth t q 0 | _ => 0 end) true
              | _ => true
              end in
            if negb labels_ok then Some Undecided else
            if negb (trie_ok t phi e) then Some Undecided else
            if negb (le_ext (Some (U t)) (get phi O)) then Some Undecided else None
        end
    | _ => Some BadInput
    end.

  Fixpoint check_types (t : nat) (rs : list typerec) : option verdict :=
    match rs with
    | [] => None
    | r :: rs' => match check_type t r with Some v => Some v | None => check_types (S t) rs' end
    end.

  (** The optional counterexamples: a walk of the game cheaper than the profile refutes it. *)
  Definition counter_ok (ce : nat * list nat) : option verdict :=
    let '(t, w) := ce in
    if negb (Nat.ltb t N) || negb (walk_ok true w) || negb (walk_defined w) then Some BadInput else
    if ltb (walk_cost t w) (U t) then Some Refuted else None.

  Fixpoint first_some {A} (f : A -> option verdict) (l : list A) : option verdict :=
    match l with [] => None | x :: l' => match f x with Some v => Some v | None => first_some f l' end end.

  (** ** The guarantee rule ([guarantee.GuaranteeRule], K.7). *)
  Definition gh : list Q := match crule C with RGuarantee h _ => h | _ => [] end.
  Definition gextras : list (list nat) := match crule C with RGuarantee _ ex => ex | _ => [] end.

  (** The normals: the 0/1 vectors (by their bit masks 1 .. 2^N − 1), then the extras. *)
  Definition bitq (m i : nat) : Q := if Nat.testbit m i then 1 else 0.
  Definition normals : list (list Q) :=
    map (fun m => map (bitq m) (seq 0 N)) (seq 1 (2 ^ N - 1)) ++
    map (fun a => map (fun x => inject_Z (Z.of_nat x)) a) gextras.

  Definition dotq (a b : list Q) : Q := fold_right Qplus 0 (map (fun p => fst p * snd p) (combine a b)).

  (** [_solve]: the unique x with Σ_j x_j cols[j] = rhs, by Gauss–Jordan
      elimination ([None] when the columns are dependent or rhs is not in
      their span). *)
  Fixpoint find_pivot (rows : list (list Q)) (j r : nat) : option nat :=
    match rows with
    | [] => None
    | row :: rows' => if Nat.leb j r && negb (Qeq_bool (nth j row 0) 0) then Some r
                      else find_pivot rows' j (S r)
    end.

  Definition swap {A} (l : list A) (i k : nat) (d : A) : list A :=
    map (fun r => if Nat.eqb r i then nth k l d else if Nat.eqb r k then nth i l d else nth r l d)
        (seq 0 (length l)).

  Definition elim (rows : list (list Q)) (j : nat) : option (list (list Q)) :=
    match find_pivot rows j O with
    | None => None
    | Some p =>
        let rs := swap rows j p [] in
        let pr := nth j rs [] in
        let pr' := map (fun x => x / nth j pr 0) pr in
        Some (map (fun r => let row := nth r rs [] in
                            if Nat.eqb r j then pr'
                            else let f := nth j row 0 in map (fun pq => fst pq - f * snd pq) (combine row pr'))
                  (seq 0 (length rs)))
    end.

  Fixpoint gauss (rows : list (list Q)) (j k : nat) : option (list (list Q)) :=
    match k with
    | O => Some rows
    | S k' => match elim rows j with Some rs => gauss rs (S j) k' | None => None end
    end.

  Definition solve (cols : list (list Q)) (rhs : list Q) : option (list Q) :=
    let k := length cols in
    let rows := map (fun i => map (fun c => nth i c 0) cols ++ [nth i rhs 0]) (seq 0 (length rhs)) in
    match gauss rows O k with
    | None => None
    | Some rs => if existsb (fun row => negb (Qeq_bool (nth k row 0) 0)) (skipn k rs) then None
                 else Some (map (fun j => nth k (nth j rs []) 0) (seq 0 k))
    end.

  (** [vertices]: every basic feasible solution with positive support, bases
      of 1 .. length rhs columns in lexicographic order; [None] beyond the
      kernel's bound of 20,000 bases. *)
  Fixpoint choose (k : nat) (l : list nat) : list (list nat) :=
    match k, l with
    | O, _ => [[]]
    | S _, [] => []
    | S k', x :: l' => map (cons x) (choose k' l') ++ choose k l'
    end.

  Definition max_bases : Z := 20000.

  Definition vertices (cols : list (list Q)) (rhs : list Q) : option (list (list Q)) :=
    let bases := flat_map (fun k => choose k (seq 0 (length cols))) (seq 1 (length rhs)) in
    if Z.ltb max_bases (Z.of_nat (length bases)) then None else
    Some (flat_map (fun K =>
      match solve (map (fun j => nth j cols []) K) rhs with
      | Some x => if forallb (fun v => ltb 0 v) x
                  then [map (fun j => match find_index j K with Some i => nth i x 0 | None => 0 end)
                            (seq 0 (length cols))]
                  else []
      | None => []
      end) bases).

  (** Extended (+∞) combinations of label rows: Σ_j c_j rows_j(v) over c_j ≠ 0. *)
  Definition combine_at (c : list Q) (rows : list (list (option Q))) (v : nat) : option Q :=
    fold_right (fun jc acc => if Qeq_bool (fst jc) 0 then acc else
                              match acc, get (nth (snd jc) rows []) v with
                              | Some x, Some y => Some (x + fst jc * y)
                              | _, _ => None
                              end)
               (Some 0) (combine c (seq 0 (length c))).

  Definition orelax (f : nat -> option Q) (k : Q) (v : nat) : option Q :=
    fold_right (fun a acc => omin (oadd (k * snd a) (f (fst a))) acc) None (arcs v).

  (** [labels] for the guarantee's rows: N lists of n integers or null, +∞ at dead nodes. *)
  Definition glabels (xs : option (list (option Z))) : option (list (option Q)) :=
    node_labels (match xs with Some l => Some (Some l) | None => Some None end).

  Fixpoint all_some {A} (l : list (option A)) : option (list A) :=
    match l with [] => Some [] | Some x :: l' => option_map (cons x) (all_some l') | None :: _ => None end.

  Definition le_a (b a : list Q) : bool := forallb (fun p => Qle_bool (fst p) (snd p)) (combine b a).
  Definition leqq (a b : list Q) : bool := Nat.eqb (length a) (length b) && forallb (fun p => Qeq_bool (fst p) (snd p)) (combine a b).
  Definition qmaxl (a : list Q) : Q := fold_right qmax2 0 a.

  (** The DP's equations for normal [i]: at the goals m_a(g) = a·d(g, g^.);
      elsewhere m_a(v) = min(steps, dominated covers). *)
  Definition dp_ok (m : list (list (option Q))) (i : nat) : option verdict :=
    let A := normals in
    let a := nth i A [] in
    let mi := nth i m [] in
    if negb (forallb (fun g => match get mi g with
                              | Some x => Qeq_bool x (dotq a (map (fun j => Dv j g) types))
                              | None => false end) (goals I)) then Some Undecided else
    let dom := filter (fun j => negb (leqq (nth j A []) a) && le_a (nth j A []) a) (seq 0 (length A)) in
    match (if Nat.eqb (length dom) O then Some [] else vertices (map (fun j => nth j A []) dom) a) with
    | None => Some Undecided
    | Some table =>
        let best := fun v =>
          if isgoal v then get mi v else
          fold_right (fun c acc => omin acc (combine_at c (map (fun j => nth j m []) dom) v))
                     (orelax (get mi) (qmaxl a) v) table in
        if forallb (fun v => oeq (best v) (get mi v)) (seq 0 n) then None else Some Undecided
    end.

  Fixpoint first_v (f : nat -> option verdict) (l : list nat) : option verdict :=
    match l with [] => None | x :: l' => match f x with Some v => Some v | None => first_v f l' end end.

  (** The covers: each a list of one number >= 0 per normal. *)
  Definition covers_ok (cs : list nums) : option (list (list Q)) :=
    all_some (map (fun c => match c with
                            | NList l => if Nat.eqb (length l) (length normals) then
                                           match all_some l with
                                           | Some mu => if forallb (fun x => Qle_bool 0 x) mu then Some mu else None
                                           | None => None end
                                         else None
                            | NBad => None end) cs).

  Definition ydir (lam : list Q) : list Q :=
    map (fun i => dotq lam (map (fun a => nth i a 0) normals)) (seq 0 N).

  (** The packing polytope's vertices (the normals' coordinates of the basic
      solutions of Σ λ_a a + slack = 1) that the DP's equations do not imply:
      the arc condition's directions; [None] beyond the kernel's bound. *)
  Definition implied (lam : list Q) : bool :=
    let y := ydir lam in
    let nz := length (filter (fun x => negb (Qeq_bool x 0)) lam) in
    Nat.eqb nz O || (Nat.eqb nz 1 && Qeq_bool (qmaxl y) 1) ||
    (negb (Nat.ltb (2 ^ N - 1) (length normals)) && forallb (fun x => Qeq_bool x 0 || Qeq_bool x 1) y).

  Definition arc_dirs : option (list (list Q)) :=
    let units := map (fun j => map (fun i => if Nat.eqb i j then 1 else 0) (seq 0 N)) (seq 0 N) in
    match vertices (normals ++ units) (repeat 1 N) with
    | None => None
    | Some vs => Some (filter (fun lam => negb (implied lam)) (map (firstn (length normals)) vs))
    end.

  (** The arc condition in those directions: the least cover bound of y_λ·r
      on F_v is at most w + λ·m(u) on every arc of every non-goal node. *)
  Definition arc_ok (m : list (list (option Q))) (mus : list (list Q)) : option verdict :=
    match arc_dirs with
    | None => Some Undecided
    | Some ds =>
        if forallb (fun lam =>
          let cands := filter (fun mu => leqq (ydir mu) (ydir lam)) mus ++ [lam] in
          forallb (fun v => isgoal v ||
            le_ext (fold_right (fun mu acc => omin (combine_at mu m v) acc) None cands)
                   (orelax (combine_at lam m) 1 v)) (seq 0 n)) ds
        then None else Some Undecided
    end.

  (** The priority order: by decreasing prior, ties by index. *)
  Fixpoint insert_by (t : nat) (l : list nat) : list nat :=
    match l with
    | [] => [t]
    | x :: l' => if ltb (priorq x) (priorq t) || (Qeq_bool (priorq x) (priorq t) && Nat.ltb t x)
                 then t :: l else x :: insert_by t l'
    end.
  Definition order : list nat := fold_right insert_by [] (rev types).

  (** [_step]: σ of a prefix entering [u] from state [r], a point of F and the
      lexicographic minimum by one dual per stage. *)
  Definition nums_k (x : nums) (k : nat) : option (list Q) :=
    match x with NList l => if Nat.eqb (length l) k then all_some l else None | NBad => None end.

  (** Stage by stage from [k]: the dual parses ([BadInput] otherwise) and proves
      σ_{o_k} minimal ([Undecided] otherwise). *)
  Definition stage_holds (A : list (list Q)) (o : list nat) (sg beta : list Q) (k : nat)
             (y fx : list Q) (z : Q) : bool :=
    forallb (fun x => Qle_bool 0 x) y &&
    forallb (fun i => Qle_bool (dotq y (map (fun a => nth i a 0) A) + z +
                                dotq fx (map (fun j => if Nat.eqb j i then 1 else 0) o))
                               (if Nat.eqb i (nth k o O) then 1 else 0)) (seq 0 N) &&
    Qle_bool (nth (nth k o O) sg 0) (dotq y beta + z + dotq fx (map (fun j => nth j sg 0) o)).

  Fixpoint stages (A : list (list Q)) (o : list nat) (sg beta : list Q) (k : nat) (ds : list dualrec)
    : option verdict :=
    match ds with
    | [] => None
    | d :: ds' =>
        match nums_k (dy d) (length A), nums_k (dfix d) k, dz d with
        | Some y, Some fx, Some z =>
            if stage_holds A o sg beta k y fx z then stages A o sg beta (S k) ds' else Some Undecided
        | _, _, _ => Some BadInput
        end
    end.

  Definition step_ok (m : list (list (option Q))) (rec : steprec) (r : list Q) (u : nat) (wt0 : Q)
    : verdict + list Q :=
    let A := normals in
    let o := order in
    match nums_k (ssigma rec) N with
    | None => inl BadInput
    | Some sg =>
      match sduals rec with
      | None => inl BadInput
      | Some duals =>
        if negb (Nat.eqb (length duals) (N - 1)) then inl BadInput else
        match all_some (map (fun i => get (nth i m []) u) (seq 0 (length A))) with
        | None => inl Undecided
        | Some mu =>
          let beta := map (fun i => (dotq (nth i A []) r - nth i mu 0) / wt0) (seq 0 (length A)) in
          if negb (forallb (fun x => Qle_bool 0 x) sg && Qeq_bool (qsum sg) 1 &&
                   forallb (fun i => Qle_bool (nth i beta 0) (dotq (nth i A []) sg)) (seq 0 (length A)))
          then inl Undecided else
          match stages A o sg beta O duals with Some v => inl v | None => inr sg end
        end
      end
    end.

  (** σ at every prefix of the profile's walks, in the canonical order (the mass
      trie's), with the rule's state after each (r_0 = h, r ← r − w σ). *)
  Definition tentry := (list Q * list Q)%type.   (* σ at the prefix, the state after it *)

  Definition parent_state (acc : list tentry) (p : list nat) : list Q :=
    match index_of p mass_trie with Some j => snd (nth j acc ([], gh)) | None => gh end.

  Fixpoint run_steps (m : list (list (option Q))) (steps : list steprec) (todo : list (list nat))
           (q : nat) (acc : list tentry) : option verdict * list tentry :=
    match todo with
    | [] => (None, acc)
    | pq :: todo' =>
        let p := removelast pq in
        let u := last pq O in
        let r := parent_state acc p in
        let wt0 := wt (last p O) u in
        if Nat.leb (length steps) q then (Some BadInput, acc) else
        match step_ok m (nth q steps (mkStep NBad None)) r u wt0 with
        | inl v => (Some v, acc)
        | inr sg => run_steps m steps todo' (S q)
                      (acc ++ [(sg, map (fun i => nth i r 0 - wt0 * nth i sg 0) (seq 0 N))])
        end
    end.

  Definition gtable (gw : gwit) (m : list (list (option Q))) : option verdict * list tentry :=
    match gsteps gw with
    | None => (Some BadInput, [])
    | Some steps =>
        match run_steps m steps mass_trie O [] with
        | (Some v, acc) => (Some v, acc)
        | (None, acc) => (if Nat.eqb (length steps) (length mass_trie) then None else Some BadInput, acc)
        end
    end.

  (** The costs and the greedy test with the certified σ. *)
  Definition gsig_t (tab : list tentry) (p : list nat) (v t : nat) : Q :=
    match index_of (p ++ [v]) mass_trie with Some i => nth t (fst (nth i tab ([], []))) 0 | None => 0 end.

  Fixpoint gwcost (tab : list tentry) (t : nat) (p : list nat) (l : list nat) : Q :=
    match l with
    | [] => Dv t (last p O)
    | v :: l' => wt (last p O) v * gsig_t tab p v t + gwcost tab t (p ++ [v]) l'
    end.

  Definition gU (tab : list tentry) (t : nat) : Q :=
    qsum (map (fun e => snd e * gwcost tab t (firstn 1 (fst e)) (tl (fst e))) (nth t (mix C) [])).

  Definition ggreedy_at (tab : list tentry) (p : list nat) : bool :=
    let top := qmax (map (fun t => mass t p) types) in
    forallb (fun i => negb (ltb 0 top && ltb 0 (gsig_t tab (removelast p) (last p O) i) && ltb (mass i p) top)) types.

  Definition decide_guarantee (gw : gwit) : verdict :=
    let A := normals in
    if negb (Nat.eqb (length (gm gw)) (length A)) then BadInput else
    match all_some (map glabels (gm gw)) with
    | None => BadInput
    | Some m =>
      match first_v (dp_ok m) (seq 0 (length A)) with
      | Some v => v
      | None =>
        if negb (forallb (fun i => le_ext (Some (dotq (nth i A []) gh)) (get (nth i m []) (start I)))
                         (seq 0 (length A))) then Undecided else
        match covers_ok (gcovers gw) with
        | None => BadInput
        | Some mus =>
          match arc_ok m mus with
          | Some v => v
          | None =>
            match gtable gw m with
            | (Some v, _) => v
            | (None, tab) =>
                if negb (forallb (ggreedy_at tab) mass_trie) then Refuted else
                if forallb (fun t => Qle_bool (gU tab t) (nth t gh 0)) types then Pass else Undecided
            end
          end
        end
      end
    end.
End Kernel.

(** ** The decision ([check._decide]), in its order. *)
Definition decide (I : instance) (P : profile) (W : witness) : verdict :=
  if negb (instance_ok I) then BadInput else
  match read_profile I P with
  | None => Refuted
  | Some C =>
      if negb (Z.ltb 0 (denominator W)) then BadInput else
      if negb (dist_shape_ok I W) then BadInput else
      if negb (distances_ok I W) then Undecided else
      if negb (reach_ok I W) then BadInput else
      match crule C with
      | RGuarantee _ _ =>
          if has_types W || has_counterexamples W then BadInput else
          match wguarantee W with
          | Some (Some gw) => decide_guarantee I W C gw
          | _ => BadInput
          end
      | RTable _ _ _ =>
          if match wguarantee W with Some _ => true | None => false end then BadInput else
          if negb (forallb (walk_defined I W C) (all_walks C)) then Refuted else
          if negb (greedy_ok I W C) then Refuted else
          match first_some (counter_ok I W C) (counterexamples W) with
          | Some v => v
          | None =>
              match wtypes W with
              | Some rs =>
                  if negb (Nat.eqb (length rs) (N I)) then BadInput else
                  match check_types I W C O rs with Some v => v | None => Pass end
              | None => BadInput
              end
          end
      end
  end.
