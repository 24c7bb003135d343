"""How a run ended: the status codes of both engines (the compiled kernel and the Python solver loop), in one place."""

FINISHED = 0  # reached the end of the run
FAILED = -1  # the step size collapsed
BUDGET = -2  # the evaluation budget or the priced work budget is spent
NONFINITE = -3  # the state became non-finite
ENERGY = -4  # the energy watch saw energy created (a numerical instability)
PROJECTED = -5  # stopped early: its pace projects far over the computing budget (exit 2, like a refusal)
SWITCH = -6  # stopped to go on on the compiled engine: its pace on scipy projected far over the prediction
INTERRUPTED = -7  # the compiled kernel saw its stop flag (a signal arrived: gearcli.core.signals.deferred)

#: the kernel's parameter vector ``wpar`` (gearcli.engine.guards.WP_*) may carry one more entry at this index: the
#: kernel writes the time it has reached there at every priced-budget check (every cost.BUDGET_CHECK_EVERY
#: accepted steps), for a progress bar polled from another thread; the numbers of the run do not depend on it
WP_PROGRESS = 15

#: and one more after it: the stop flag, set (to 1.0) by a signal handler from the main thread while the kernel runs in
#: a worker thread; the kernel reads it after every accepted step and returns with :data:`INTERRUPTED`
WP_STOP = 16

#: and one more after that: the step ceiling (s), scipy's ``max_step``: the initial step and every step are clamped
#: to it (an explicit method's stability limit, :func:`gearcli.simulate.choice.stability_step`; Radau's on a
#: time-varying contact length, :func:`gearcli.simulate.solver.contact_step`); absent, no ceiling
WP_MAX_STEP = 17
