"""eomc from Python: load a spec, run it, linearize it, measure its accuracy.

    import eomc
    m = eomc.load("specs/chain5.yaml")      # built once, then from eomc's cache
    m.set(l1=1.5)                           # parameters, or inputs held constant
    a = m.accel(q, v)                       # q'' at a state, as a numpy array
    r = m.run(t_end=5, init={"q1": 1.0})    # numpy arrays by column name
    r["t"], r["q1"], r["q1'"], r.columns

A loaded model is a shared library (``eomc build --shared``) holding the
model and the runtime, called through ctypes; nothing is compiled for
Python.  ``run``, ``linearize``, ``equilibrium``, ``accuracy`` and
``reference`` go through the simulator's own command line inside that
library (``eomc_main_mem``): the same options, the same checks, the same
numbers to the last bit as ``eomc run`` writes, the same messages.  What
the command line would print as a warning becomes an :class:`EomcWarning`;
an error becomes :class:`SpecError`, :class:`UsageError` or
:class:`NumericalFailure` with eomc's message.  Any other keyword of those
methods is the simulator option of that name (``atol=1e-9`` is
``--atol 1e-9``, ``stabilize="project"`` is ``--stabilize project``,
``stats=True`` is ``--stats``); ``EXE --help`` lists them.

Nothing is global: each model has its own library handle and simulator,
and each call its own runtime state, so two models work side by side and
runs in threads do not interfere (ctypes releases the GIL while they run).
"""

from ._errors import (ControllerError, EomcError, EomcWarning, FileNotFound, NumericalFailure,
                      SpecError, UsageError)
from ._model import Linearization, Model, Run, Sim, load

__all__ = ["load", "Model", "Run", "Linearization", "Sim", "EomcError", "SpecError",
           "UsageError", "NumericalFailure", "ControllerError", "FileNotFound", "EomcWarning"]
