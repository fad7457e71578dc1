"""The graph layer: the CSR graph (:mod:`~solver.graph.network`), exact shortest distances
(:mod:`~solver.graph.distances`) and deterministic shortest paths with the documented tie-break
(:mod:`~solver.graph.shortest_paths`)."""
