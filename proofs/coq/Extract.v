(** * Extraction of the kernel's decision to OCaml.

    Only renamings of Coq's own inductive types to OCaml's (booleans, lists,
    pairs, options); numbers stay Coq's binary [positive]/[Z]/[Q] and unary
    [nat], so the extracted arithmetic is exactly the proved one. *)

From DPP Require Import Kernel.
Require Extraction.
Extraction Language OCaml.
Extract Inductive bool => "bool" [ "true" "false" ].
Extract Inductive sumbool => "bool" [ "true" "false" ].
Extract Inductive list => "list" [ "[]" "(::)" ].
Extract Inductive prod => "( * )" [ "(,)" ].
Extract Inductive option => "option" [ "Some" "None" ].
Extraction "extracted/kernel.ml" decide.
