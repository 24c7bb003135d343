"""The design check (``gearcli design``): geometry, kinematics, stiffness, static forces, warnings.

Pure ``math``; never imports scipy (``gearcli design`` must start fast). Modules, one concern each:

- ``geometry``    ISO 21771 involute geometry of a pair, contact ratios, undercut and tip limits
- ``kinematics``  ratios, shaft speeds down the train, torques back up from the load
- ``forces``      static tooth forces on the pinion's reference circle
- ``stiffness``   Hertz (seed section 3.3), ISO 6336-1 method B, the contact law's coefficient K
- ``inertia``     gear and shaft inertias
- ``checks``      design errors (``DesignError``) and warnings
- ``rating``      ISO 6336-2/-3 strength rating of a stage (``rating_factors``: ISO 6336-1, -2, -5 factors;
                  ``rating_root``: ISO 6336-3 tooth-root factors)
- ``compute``     ``compute_design``, which assembles the ``DesignResult``
"""

from gearcli.design.compute import compute_design
from gearcli.design.stiffness import contact_stiffness_N_mm_e

__all__ = ["compute_design", "contact_stiffness_N_mm_e"]
