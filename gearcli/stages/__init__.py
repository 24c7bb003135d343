"""Stage kinds as plug-ins (ARCHITECTURE.md, "Stage kinds").

A stage kind is named by the design file's stage ``type`` ("parallel" when omitted, "planetary"). What a kind
provides is split by the layer that needs it, each part (a *facet*) in the submodule at that layer:
``kinds`` (the registry, bottom layer), ``design`` (geometry, kinematics, forces, the meshes it adds to the
rating), ``model`` (its model spec and its bodies and connectors), ``io`` (its output rows and JSON). A
kind registers each facet with ``kinds.provide(type, facet, implementation)``; nothing outside this package
asks which kind a stage is. This package's ``__init__`` imports nothing, so each submodule keeps its layer.
"""
