(* The extracted kernel's driver (untrusted glue): reads token streams that translate.py
   writes (instance, profile, witness; one stream per line of standard input, or the file named
   by the first argument), builds the Coq values and prints, one line per stream, the verdict
   of the extracted Kernel.decide: pass, refuted, bad-input or undecided.  Integers arrive as
   signed binary strings ("0", "+101", "-11"), so no arithmetic happens here. *)
open Kernel

let toks : string list ref = ref []

let next () = match !toks with t :: r -> toks := r; t | [] -> failwith "unexpected end of input"

let rec nat_of_int k = if k <= 0 then O else S (nat_of_int (k - 1))
let int () = int_of_string (next ())
let nat () = nat_of_int (int ())
let count f = let k = int () in List.init k (fun _ -> f ())

(* a positive from its binary digits, most significant first *)
let pos_of_bits b =
  let n = String.length b in
  if n = 0 || b.[0] <> '1' then failwith "bad binary";
  let p = ref XH in
  for i = 1 to n - 1 do p := (if b.[i] = '1' then XI !p else XO !p) done; !p

let z_of_tok t =
  if t = "0" then Z0
  else if t.[0] = '+' then Zpos (pos_of_bits (String.sub t 1 (String.length t - 1)))
  else if t.[0] = '-' then Zneg (pos_of_bits (String.sub t 1 (String.length t - 1)))
  else failwith ("bad integer " ^ t)
let z () = z_of_tok (next ())
let pos () = match z () with Zpos p -> p | _ -> failwith "bad denominator"
let q () = let a = z () in let b = pos () in { qnum = a; qden = b }
let optz () = let t = next () in if t = "_" then None else Some (z_of_tok t)
let flag () = int () = 1

let instance () =
  let n = int () in
  let adj = List.init n (fun _ -> count (fun () -> let u = nat () in let w = q () in (u, w))) in
  let start = nat () in
  let goals = count nat in
  let prior = count q in
  { adj; start; goals; prior }

let walk () = count nat
let mixture () = count (fun () -> let w = walk () in let p = q () in (w, p))

let profile () =
  match next () with
  | "N" ->
      let ngoals = if flag () then Some (count nat) else None in
      let nmix = count mixture in
      let nrule = match next () with
        | "T" ->
            let es = count (fun () -> let w = walk () in let d = count q in (w, d)) in
            let d = match next () with "0" -> DNone | "D" -> DDist (count q) | "P" -> DProgress
                                      | t -> failwith ("bad default " ^ t) in
            RTable (es, d, O)
        | "G" -> let h = count q in let ex = count (fun () -> count nat) in RGuarantee (h, ex)
        | t -> failwith ("bad rule " ^ t) in
      PN { ngoals; nmix; nrule }
  | "2" ->
      let tprimary = nat () in let tsecondary = nat () in
      let tmix_primary = mixture () in let tmix_secondary = mixture () in
      let trgoal = nat () in
      let trule = match next () with
        | "P" -> R2Progress
        | "T" ->
            let es = count (fun () -> let w = walk () in let p = q () in (w, p)) in
            let d = match next () with "0" -> D2None | "P" -> D2Progress | "D" -> D2Prob (q ())
                                      | t -> failwith ("bad default " ^ t) in
            R2Table (es, d)
        | "O" -> R2Other
        | t -> failwith ("bad rule " ^ t) in
      P2 { tprimary; tsecondary; tmix_primary; tmix_secondary; trgoal; trule }
  | t -> failwith ("bad profile kind " ^ t)

let labels () = match next () with
  | "-" -> None | "!" -> Some None | "+" -> Some (Some (count optz)) | t -> failwith ("bad labels " ^ t)

let optq () = match !toks with "_" :: r -> toks := r; None | _ -> Some (q ())
let nums () = match next () with
  | "!" -> NBad | "+" -> NList (count optq) | t -> failwith ("bad numbers " ^ t)
let dual () = let dy = nums () in let dfix = nums () in let dz = optq () in { dy; dfix; dz }
let steprec () =
  let ssigma = nums () in
  let sduals = match next () with "!" -> None | "+" -> Some (count dual) | t -> failwith t in
  { ssigma; sduals }
let guarantee () = match next () with
  | "-" -> None
  | "!" -> Some None
  | "+" ->
      let gm = count (fun () -> match next () with
        | "!" -> None | "+" -> Some (count optz) | t -> failwith ("bad labels " ^ t)) in
      let gcovers = count nums in
      let gsteps = match next () with "!" -> None | "+" -> Some (count steprec) | t -> failwith t in
      Some (Some { gm; gcovers; gsteps })
  | t -> failwith ("bad guarantee " ^ t)

let witness () =
  let denominator = z () in
  let distances = if flag () then Some (count (fun () -> count optz)) else None in
  let counterexamples = count (fun () -> let t = nat () in let w = walk () in (t, w)) in
  let wtypes = if flag () then Some (count (fun () ->
      let rec_ok = flag () in let rtrie = labels () in let rexit = labels () in
      let rP = labels () in let rQ = labels () in { rec_ok; rtrie; rexit; rP; rQ })) else None in
  let has_types = flag () in
  let has_counterexamples = flag () in
  let wguarantee = guarantee () in
  { denominator; distances; counterexamples; wtypes; has_types; has_counterexamples; wguarantee }

let verdict_of_line line =
  toks := List.filter (fun t -> t <> "") (String.split_on_char ' ' line);
  match !toks with
  | "VERDICT" :: v :: _ -> v
  | _ ->
      let i = instance () in
      let p = profile () in
      let w = witness () in
      if !toks <> [] then failwith "trailing tokens";
      (match decide i p w with
       | Pass -> "pass" | Refuted -> "refuted" | BadInput -> "bad-input" | Undecided -> "undecided")

let () =
  let ic = if Array.length Sys.argv > 1 then open_in Sys.argv.(1) else stdin in
  (try
     while true do
       let line = String.trim (input_line ic) in
       if line <> "" then begin
         let v = try verdict_of_line line with Failure m -> "error: " ^ m in
         print_endline v; flush stdout
       end
     done
   with End_of_file -> ())
