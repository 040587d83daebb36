(* The oracle's driver: reads a scene, calls an extracted state function for
   each time, prints one JSON line per time in the conventions of
   `sticky run --json` (numbers as strings in lowest terms, clusters as
   [first, size] with particles indexed from 0).

   Input (stdin): first line `N r`, then N lines `x_i u_i`; every number an
   exact rational `p/q` or an integer. Arguments: the times (exact
   rationals, >= 0), optionally preceded by `--dynamics`. A bad input is one
   line on stderr and exit code 1.

   Two extracted computations of the same state, both returning the whole
   state (positions, velocities, multipliers, clusters) in one record:
   - by default the proved PAVA (Sticky.Oracle.state_at: positions proved
     = P_K(x0 + t u0), velocities proved = the right derivative, multipliers
     proved = Multipliers.multiplier, clusters proved = the contact clusters
     of the positions), which is O(N) per time; for N <= cross_check_max_n
     the event-driven path (below) is run too and the two states must be
     equal field by field, else exit code 2;
   - with `--dynamics`, Sticky.DynamicsState.dynamics_state: the
     event-driven dynamics (Sticky.Dynamics.dynamics) with its multipliers
     (proved = Multipliers.multiplier) and its contact clusters, for any N
     (it is quadratic in N or worse). DynamicsState.dynamics_state_is_state_at
     proves the two paths equal for t > 0.

   This file is the only unproved part besides the extraction itself: it
   parses, checks admissibility (r > 0, gaps >= 2r, no approaching contact,
   as the crate's InitialData::new), chooses the path, compares the two
   states of the cross-check, and prints. It does no arithmetic on the
   state; the comparisons are the extracted Qle_bool/Qeq_bool. *)

module Zr = Z (* zarith's integers, before the extracted module shadows Z *)

open Sticky_oracle

(* Up to this N the default path also runs the event-driven dynamics. *)
let cross_check_max_n = 64

exception Bad of string

let fail fmt = Printf.ksprintf (fun s -> raise (Bad s)) fmt

let is_digits s = s <> "" && String.for_all (fun c -> c >= '0' && c <= '9') s

(* An exact rational `p/q` or integer `p`, optional sign on p. *)
let parse_q what s =
  let sign, body =
    if s <> "" && (s.[0] = '-' || s.[0] = '+') then
      (if s.[0] = '-' then -1 else 1), String.sub s 1 (String.length s - 1)
    else 1, s
  in
  let num, den =
    match String.index_opt body '/' with
    | None -> body, "1"
    | Some k -> String.sub body 0 k, String.sub body (k + 1) (String.length body - k - 1)
  in
  if not (is_digits num && is_digits den) then fail "%s: not an exact rational: %S" what s;
  let n = Zr.of_string num and d = Zr.of_string den in
  if Zr.sign d = 0 then fail "%s: zero denominator: %S" what s;
  qred { qnum = (if sign < 0 then Zr.neg n else n); qden = d }

let render (x : q) =
  let x = qred x in
  if Zr.equal x.qden Zr.one then Zr.to_string x.qnum
  else Zr.to_string x.qnum ^ "/" ^ Zr.to_string x.qden

let words line = List.filter (fun w -> w <> "") (String.split_on_char ' '
  (String.map (fun c -> if c = '\t' || c = '\r' then ' ' else c) line))

let zero = { qnum = Zr.zero; qden = Zr.one }

let read_scene () =
  let lines = ref [] in
  (try
     while true do
       let l = input_line stdin in
       if words l <> [] then lines := l :: !lines
     done
   with End_of_file -> ());
  match List.rev !lines with
  | [] -> fail "empty input: expected a first line `N r`"
  | header :: rest ->
    let n, r =
      match words header with
      | [n; r] ->
        if not (is_digits n) then fail "first line: N is not a positive integer: %S" n;
        let n = int_of_string n in
        if n < 1 then fail "first line: N must be at least 1";
        n, parse_q "radius" r
      | _ -> fail "first line: expected `N r`, got %S" header
    in
    if List.length rest <> n then
      fail "expected %d particle lines `x_i u_i`, got %d" n (List.length rest);
    let parse_line i l =
      match words l with
      | [x; u] -> parse_q (Printf.sprintf "positions[%d]" i) x,
                  parse_q (Printf.sprintf "velocities[%d]" i) u
      | _ -> fail "particle %d (indices from 0): expected `x u`, got %S" i l
    in
    let xu = List.mapi parse_line rest in
    let x = List.map fst xu and u = List.map snd xu in
    if qle_bool r zero then fail "radius must be positive, got %s" (render r);
    let two_r = qplus r r in
    let xa = Array.of_list x and ua = Array.of_list u in
    for i = 0 to n - 2 do
      let gap = qminus xa.(i + 1) xa.(i) in
      if not (qle_bool two_r gap) then
        fail "pair (%d, %d) overlaps (indices from 0): gap %s < 2r = %s"
          i (i + 1) (render gap) (render two_r);
      if qeq_bool two_r gap && not (qle_bool ua.(i) ua.(i + 1)) then
        fail "pair (%d, %d) in contact approaches (indices from 0): velocities %s > %s"
          i (i + 1) (render ua.(i)) (render ua.(i + 1))
    done;
    n, r, x, u

let json_strings l = "[" ^ String.concat ", " (List.map (fun v -> "\"" ^ render v ^ "\"") l) ^ "]"

let json_clusters l =
  "[" ^ String.concat ", " (List.map (fun (f, s) -> Printf.sprintf "[%d, %d]" f s) l) ^ "]"

let same_values a b = List.length a = List.length b && List.for_all2 qeq_bool a b

(* The first field in which two states differ, if any. *)
let differing_field s d =
  if not (same_values s.st_positions d.st_positions) then Some "positions"
  else if not (same_values s.st_velocities d.st_velocities) then Some "velocities"
  else if not (same_values s.st_multipliers d.st_multipliers) then Some "multipliers"
  else if s.st_clusters <> d.st_clusters then Some "clusters"
  else None

let print_state n r t s =
  Printf.printf
    "{\"n\": %d, \"radius\": \"%s\", \"t\": \"%s\", \"positions\": %s, \"velocities\": %s, \"multipliers\": %s, \"clusters\": %s}\n"
    n (render r) (render t) (json_strings s.st_positions) (json_strings s.st_velocities)
    (json_strings s.st_multipliers) (json_clusters s.st_clusters)

exception Disagree of string

let () =
  try
    let args = List.tl (Array.to_list Sys.argv) in
    let use_dynamics, times =
      match args with "--dynamics" :: rest -> true, rest | _ -> false, args in
    if times = [] then
      fail "usage: oracle [--dynamics] T... < scene (first line `N r`, then N lines `x u`)";
    let times = List.map (fun s -> let t = parse_q "time" s in
                           if not (qle_bool zero t) then fail "negative time %s" (render t);
                           t) times in
    let n, r, x, u = read_scene () in
    List.iter (fun t ->
        if use_dynamics then print_state n r t (dynamics_state r t x u)
        else begin
          let s = state_at r t x u in
          if n <= cross_check_max_n then
            Option.iter (fun what ->
                raise (Disagree (Printf.sprintf
                  "PAVA and the event-driven dynamics differ in %s at t = %s" what (render t))))
              (differing_field s (dynamics_state r t x u));
          print_state n r t s
        end)
      times
  with
  | Bad msg -> prerr_endline ("oracle: " ^ msg); exit 1
  | Disagree msg -> prerr_endline ("oracle: internal cross-check failed: " ^ msg); exit 2
