"""The two-goal construction (N = 2, the paper's Sections IV-V): σ* (:mod:`~.progress`), ξ²
(:mod:`~.secondary`), its phases (:mod:`~.phases`), the primary's mixture (:mod:`~.primary`), the
exact evaluation of two-goal pairs (:mod:`~.evaluation`), the equilibrium
(:mod:`~.equilibrium`), its ``dpp-profile/1`` document (:mod:`~.profile_json`) and text
(:mod:`~.report`)."""
