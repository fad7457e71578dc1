"""The solver's own readers of documents and arrays, below the game model: bounded JSON text
with exact numbers (:mod:`~solver.formats.json_text`), JSON node ids
(:mod:`~solver.formats.nodes`), MovingAI ``.map`` grids (:mod:`~solver.formats.movingai`) and
the parts of a compact ``dpp-map-instance/1`` (:mod:`~solver.formats.map_instance`). This layer
builds documents and arrays, never game objects."""
