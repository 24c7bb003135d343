"""Rating standards as plug-ins (issue 34, plug-in seams; docs/iso6336.md, "Rating standards").

A strength-rating standard is a module and one :func:`register` call; the design file picks it by
``[rating] standard`` (default ``"iso6336"``). Nothing outside a standard's module asks which standard rated a mesh:
design, the facade's simulated-K_v re-rating, life, io and report ask the standard (:class:`RatingStandard`) and
read its rated meshes through :class:`RatedMesh` (safety factors, the factor table by name) and its S–N curves
(:class:`~gearcli.rating.sn.SNCurve`, per member and failure mode).

- ``standard``  the protocols: :class:`RatingStandard`, :class:`RatedMesh`, :class:`RatedMember`
- ``registry``  :func:`register`, :func:`standard` (by the ``[rating] standard`` name), :func:`for_rating` (by a
                rated mesh's ``standard`` title), :func:`names`
- ``dynamic``   the simulated dynamic factor of a run (max |F_t| over the static F_t), standard-free
- ``sn``        S–N curves as nodes of a life-factor curve, the Miner variants below the knee

This package sits below the design layer: ISO 6336 (``gearcli.design.iso6336``) registers itself when the design
layer is imported; a test or an extension registers its own the same way.
"""

from gearcli.rating.registry import DEFAULT, for_rating, names, register, standard
from gearcli.rating.standard import MODES, RatedMember, RatedMesh, RatingStandard

__all__ = ["DEFAULT", "MODES", "RatedMember", "RatedMesh", "RatingStandard", "for_rating", "names", "register",
           "standard"]
