"""The game model: the instance (:mod:`~solver.game.instance`), reading and writing its JSON
(:mod:`~solver.game.instance_reading`, :mod:`~solver.game.instance_writing`), the instance on
node indices with its distance fields (:mod:`~solver.game.indexed_instance`) and one walk of a
mixed strategy (:mod:`~solver.game.walks`)."""
