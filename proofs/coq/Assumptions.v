(** * What the main theorems rest on: each must print "Closed under the
    global context" (nothing assumed anywhere below them). *)
From DPP Require Import Tel Defender Converse Pbne Distances KSound Guarantee KSoundG.
Print Assumptions Tel.tel4.
Print Assumptions Defender.greedy_seq_rational.
Print Assumptions Converse.optimal_greedy.
Print Assumptions Pbne.pbne_of_checks.
Print Assumptions Distances.bellman_exact.
Print Assumptions KSound.kernel_sound.
Print Assumptions KSound.kernel_defender_optimal.
Print Assumptions Guarantee.stage_check_lexmin.
Print Assumptions Guarantee.cover_bound.
Print Assumptions Guarantee.guarantee_pbne.
Print Assumptions KSoundG.kernel_sound_guarantee.
