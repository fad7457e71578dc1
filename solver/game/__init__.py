"""The game model: the instance (:mod:`~solver.game.instance`), reading and writing its JSON
(:mod:`~solver.game.instance_reading`, :mod:`~solver.game.instance_writing`), one walk of a
mixed strategy (:mod:`~solver.game.walks`) and the one writer of profile documents
(:mod:`~solver.game.profile_writing`)."""
