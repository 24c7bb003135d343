"""Loads to life (docs/life.md): duty cycles and measured histories, tooth-load spectra, ISO 6336-6 Miner
damage on the S–N curves of the file's rating standard (``gearcli.rating``; ISO 6336-2/-3 by default), and ISO 281
bearing lives over the duty.

- ``duty``      the ``[[duty]]`` points, or a torque–speed history classed into points
- ``spectra``   static (the rating's stress) and dynamic (mesh-cycle peaks of a simulation) load classes
- ``miner``     the Miner sum and the spectrum safety on the standard's S–N curves (``gearcli.rating.sn``)
- ``channels``  bearing reactions as simulation channels
- ``run``       ``compute_life``: the points (evaluated by the injected facade functions) to a ``LifeResult``
- ``session``   the base file as a sweep scene, and its duty points

The facade (:func:`gearcli.api.prepare_life`, :func:`gearcli.api.life`) loads the file and evaluates the points.
"""

from gearcli.stages import life as _stage_life  # noqa: E402, F401  # registers the built-in kinds' life facets
