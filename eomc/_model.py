"""A loaded model: parameters, accelerations, and the simulator's tasks.

Direct calls (``set``, ``accel``, ``initial``) go to the runtime's API on
the model's own simulator object.  Runs and the other tasks go to the
simulator's command line inside the library, with the parameters set so
far passed as ``--set NAME=VALUE``: the numbers are those ``eomc run``
writes to its CSV, read back exactly (``repr`` of a float and eomc's
shortest-digits output both round-trip).
"""

import ctypes
import difflib
import math
import os
import tempfile
import threading
import warnings

import numpy as np

from . import _build
from ._errors import (ControllerError, EomcError, EomcWarning, FileNotFound,
                      NumericalFailure, UsageError, as_keywords, raise_for, warn_lines)
from ._lib import CONTROLLER, INCONSISTENT, Library, MainExtra, Step, as_doubles

__all__ = ["load", "Model", "Run", "Linearization", "Sim"]


def load(spec, scene=None, form=None, fix=None, extended=False, jacobian=None,
         floating=False, joint_inputs=False, parameters=False, effects=None):
    """A model from a spec (``.yaml``), an MJCF or URDF model (``.xml``,
    ``.urdf``), or a library ``eomc build --shared`` made (``.so``).

    A spec is built as ``eomc build SPEC --shared`` (with ``--scene``,
    ``--form``, ``--fix NAME=VALUE`` from the dict ``fix``, ``--extended``,
    ``--jacobian``, ``--effects`` from a list of effects' names or a
    comma-joined string), into eomc's cache, the same one ``eomc run`` uses.
    A model file is imported first, as ``eomc import`` would: ``floating``
    frees a URDF's root link, ``joint_inputs`` gives an MJCF's joints the
    inputs ``tau_J`` a URDF's have, ``parameters`` makes its masses,
    inertias, damping, stiffness and armature parameters.
    A spec eomc cannot read raises :class:`SpecError` with its place."""
    imports = [flag for flag, on in (("--floating", floating), ("--joint-inputs", joint_inputs),
                                     ("--parameters", parameters)) if on]
    if not os.path.exists(spec):
        raise FileNotFound("cannot read %s: no such file" % spec, spec)
    if spec.endswith(".so"):
        if scene or form or fix or extended or jacobian or imports or effects is not None:
            raise UsageError("%s is built already: scene, form, fix, extended, jacobian "
                             "and the import's options are a spec's" % spec)
        return Model(spec)
    if imports and not spec.endswith((".xml", ".urdf")):
        raise UsageError("floating, joint_inputs and parameters are for an MJCF or URDF "
                         "model (.xml, .urdf), and %s is a spec" % spec)
    return Model(_build.build(spec, scene, form, fix, extended, jacobian, imports, effects))


def _number(v):
    """A value as the command line reads it back exactly."""
    if isinstance(v, (bool, np.bool_)):
        raise UsageError("a number was expected, not %r" % (v,))
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    return repr(float(v))


def _set_value(name, v):
    """A value given to set() as a double, or UsageError naming it: a
    NaN or an infinity would be taken, and blamed on every later call."""
    try:
        if isinstance(v, (bool, np.bool_)):
            raise TypeError
        x = float(v)
    except (TypeError, ValueError):
        raise UsageError("set: %s = %r: a number was expected; nothing was set"
                         % (name, v)) from None
    if not math.isfinite(x):
        raise UsageError("set: %s = %r is not a finite number; nothing was set" % (name, x))
    return x


def _options(kw):
    """Keywords as the simulator's options: name_x=V is --name-x V; True a
    flag; None or False nothing; a dict NAME=VALUE pairs, each its own
    option (init, set; sweep={"theta0": "0.1:3:30"}); a list or tuple comma-joined (methods, tolerances)."""
    argv = []
    for key, value in kw.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            argv.append(flag)
        elif isinstance(value, dict):
            for name, v in value.items():
                argv += [flag, "%s=%s" % (name, v if isinstance(v, str) else _number(v))]
        elif isinstance(value, (list, tuple)):
            argv += [flag, ",".join(v if isinstance(v, str) else _number(v) for v in value)]
        elif isinstance(value, str):
            argv += [flag, value]
        else:
            argv += [flag, _number(value)]
    return argv


def _table(text):
    """A CSV's columns by name: numbers as float64 arrays (read exactly,
    empty cells NaN), other columns (a report's method names, a sweep's
    status) as arrays of str."""
    lines = text.splitlines()
    if not lines:
        return [], {}
    columns = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:] if line]
    data = {}
    for j, name in enumerate(columns):
        cells = [r[j] if j < len(r) else "" for r in rows]
        try:  # an empty cell of a number's column is NaN (a report's fixed_step)
            data[name] = np.array([float(c) if c else math.nan for c in cells],
                                  dtype=np.float64)
            if not any(cells):
                raise ValueError
        except ValueError:
            data[name] = np.array(cells, dtype=str)
    return columns, data


class Run:
    """A run's rows, by column name: ``t``, each coordinate, each speed (a
    coordinate's velocity ``name'``, or a speed of its own such as a free
    body's ``root_wx``: ``Model.speeds``), ``T``, ``V``, ``E`` (or the conserved quantity), the
    multipliers ``lambda[c]`` and residuals ``res[c]`` of constraints, and
    the scene's outputs, as float64 numpy arrays; or the rows of a report
    or sweep, by its columns.  ``messages`` holds what eomc said on stderr
    (warnings, --stats, --summary); ``stats`` the ``--stats`` lines as a
    dict of floats, each the figure to the last bit (eomc prints them in
    the shortest digits that read back); ``text`` what went to stdout
    besides the rows."""

    def __init__(self, columns, data, messages="", text=""):
        self.columns, self._data = columns, data
        self.messages, self.text = messages, text
        self.stats = {}
        for line in messages.splitlines():
            parts = line.split()
            if len(parts) == 2:
                try:
                    self.stats[parts[0]] = float(parts[1])
                except ValueError:
                    pass

    def __getitem__(self, name):
        try:
            return self._data[name]
        except KeyError:
            raise KeyError("%r is not a column; the columns are %s"
                           % (name, ", ".join(self.columns))) from None

    def __contains__(self, name):
        return name in self._data

    def __iter__(self):
        return iter(self.columns)

    def __len__(self):
        return len(self._data[self.columns[0]]) if self.columns else 0

    def keys(self):
        return list(self.columns)

    def array(self):
        """All numeric columns as one 2-D array (rows by columns)."""
        return np.column_stack([self._data[c] for c in self.columns
                                if self._data[c].dtype == np.float64])

    def __repr__(self):
        return "<eomc.Run: %d rows, columns %s>" % (len(self), ", ".join(self.columns))


class _Controller:
    """A Python controller f(t, q, v) as the runtime's eomc_controller_fn:
    its answer, a sequence in ``inputs`` order or a dict by name, written
    into the inputs; what goes wrong is kept (``error``, with the time)
    and the run told to stop (a nonzero status), to be raised after it."""

    # views of the runtime's arrays by address: a sampled controller's are
    # the same at every call, a continuous one's a few stages' (bounded)
    VIEWS_MAX = 64

    def __init__(self, model, f):
        self.f = f
        self.inputs = model.inputs
        self.index = {name: k for k, name in enumerate(model.inputs)}
        self.nq, self.nv, self.nu = len(model.coordinates), len(model.speeds), len(model.inputs)
        self.shape = (self.nu,)
        self.views = {}
        self.error, self.t = None, None
        self.cfn = CONTROLLER(self._call)  # kept alive as long as the run

    def _view(self, address, n):
        v = self.views.get((address, n))
        if v is None:
            if len(self.views) >= self.VIEWS_MAX:
                self.views.clear()
            v = self.views[address, n] = np.ctypeslib.as_array(
                (ctypes.c_double * max(n, 1)).from_address(address))[:n]
        return v

    def _fail(self, t, why, cause=None):
        self.t = t
        self.error = (ControllerError("the controller at t = %r: %s" % (t, why), t), cause)
        return 1

    def _call(self, ctx, t, q, v, u):
        try:
            out = self.f(t, self._view(q, self.nq).copy(), self._view(v, self.nv).copy())
            uv = self._view(u, self.nu)
            if type(out) is dict:
                for name, value in out.items():
                    k = self.index.get(name)
                    if k is None:
                        return self._fail(t, "%r is not an input of the model (its inputs: %s)"
                                          % (name, ", ".join(self.inputs)))
                    uv[k] = float(value)
            else:
                a = np.asarray(out, dtype=np.float64)
                if a.shape != self.shape:
                    return self._fail(t, "it returned %s values, and the model has %d inputs "
                                      "(%s)" % ("%d" % a.size if a.ndim == 1
                                                else "shape %s" % (a.shape,),
                                                self.nu, ", ".join(self.inputs)))
                uv[:] = a
            s = uv.sum()  # (NaN or an infinity among them: not finite)
            if s - s != 0:
                k = int(np.flatnonzero(~np.isfinite(uv))[0])
                return self._fail(t, "it set %s to %r" % (self.inputs[k], float(uv[k])))
            return 0
        except BaseException as e:  # (a KeyboardInterrupt too: raised after the run)
            return self._fail(t, "it raised %s: %s" % (type(e).__name__, e), e)

    def raise_after(self, rows):
        """The failure kept, raised with the rows computed before it."""
        err, cause = self.error
        if isinstance(cause, KeyboardInterrupt):
            raise cause
        err.rows = rows
        raise err from cause


class Sim:
    """A simulator object stepping one motion (``Model.sim``): ``t``, ``q``,
    ``v`` and ``u`` to read, ``q``, ``v`` and ``u`` to set (between steps:
    the motion goes on from there, as after a controller's sample), and
    ``advance(t)`` and ``step()``.  The runtime's eomc_evolve on a
    simulator of its own, with the model's parameters and held inputs as
    they were when it was made."""

    def __init__(self, model, init=None, t0=None, t_end=None, method=None, rtol=None,
                 atol=None, fixed_step=None, max_steps=None):
        lib = self._lib = model._lib
        self._model = model
        self._n, self._nv = len(model.coordinates), len(model.speeds)
        self._names = model.coordinates + model.speeds
        self._sim = lib.sim_alloc(lib.model)
        self._e = None
        if not self._sim:
            raise EomcError("%s: out of memory" % model.name)
        for name, value in model._sets.items():
            lib.sim_set(self._sim, name.encode(), value)
        q, v = model.initial()
        x = np.concatenate([q, v])
        for name, value in (init or {}).items():
            if name not in self._names:
                raise UsageError("sim: init: %r is not a coordinate or a speed (%s)"
                                 % (name, ", ".join(self._names)))
            x[self._names.index(name)] = _set_value(name, value)
        o = self._opts = lib.run_defaults(lib.model)
        for key, value in (("t0", t0), ("t_end", t_end), ("rtol", rtol), ("atol", atol),
                           ("h_fixed", fixed_step)):
            if value is not None:
                setattr(o, key, _set_value(key, value))
        if max_steps is not None:
            o.max_steps = int(max_steps)
        if method is not None:
            self._method = method.encode()  # kept: the options point to it
            o.method = self._method
        self._x = np.ascontiguousarray(x, dtype=np.float64)
        self._e = lib.evolve_alloc(self._sim, ctypes.byref(o), as_doubles(self._x))
        if not self._e:
            raise UsageError(model._error(self._sim))
        self._t = o.t0
        self._step = Step()
        self._last = not (o.t0 < o.t_end)

    def __del__(self):
        lib = getattr(self, "_lib", None)
        if lib is not None and getattr(self, "_e", None):
            lib.evolve_free(self._e)
        if lib is not None and getattr(self, "_sim", None):
            lib.sim_free(self._sim)

    @property
    def t(self):
        return self._t

    @property
    def t_end(self):
        return self._opts.t_end

    @property
    def q(self):
        return self._x[:self._n].copy()

    @q.setter
    def q(self, q):
        x = self._x.copy()
        x[:self._n] = self._vector(q, self._n, "q")
        self._restart(x)

    @property
    def v(self):
        return self._x[self._n:].copy()

    @v.setter
    def v(self, v):
        x = self._x.copy()
        x[self._n:] = self._vector(v, self._nv, "v")
        self._restart(x)

    @property
    def u(self):
        u = np.zeros(len(self._model.inputs))
        self._lib.sim_inputs(self._sim, self._t, as_doubles(u))
        return u

    @u.setter
    def u(self, u):
        names = self._model.inputs
        if isinstance(u, dict):
            items = list(u.items())
            for name, _ in items:
                if name not in names:
                    raise UsageError("sim: u: %r is not an input (%s)"
                                     % (name, ", ".join(names) or "the model has none"))
        else:
            items = list(zip(names, self._vector(u, len(names), "u")))
        for name, value in items:
            if self._lib.sim_set(self._sim, name.encode(), _set_value(name, value)) != 0:
                raise UsageError(self._model._error(self._sim))
        self._restart(None)

    def _vector(self, a, n, what):
        a = np.asarray(a, dtype=np.float64)
        if a.shape != (n,):
            raise UsageError("sim: %s needs %d entries, not %s" % (what, n, a.shape))
        if not np.all(np.isfinite(a)):
            raise UsageError("sim: %s is not finite: %s" % (what, a))
        return a

    def _restart(self, x):
        if self._last:
            raise UsageError("sim: the motion is over, at t = %r" % self._t)
        if self._lib.evolve_restart(self._sim, self._e,
                                    None if x is None else as_doubles(x)) != 0:
            raise UsageError(self._model._error(self._sim))
        if x is not None:
            self._x[:] = x

    def _took(self, rc):
        if rc != 0:
            self._last = True
            raise NumericalFailure(self._model._error(self._sim), self._t)
        d = self._step
        ctypes.memmove(self._x.ctypes.data, d.x1, 8 * len(self._x))
        self._t, self._last = d.t1, bool(d.last)

    def step(self):
        """One accepted step; returns the time reached."""
        if self._last:
            raise UsageError("sim: the motion is over, at t = %r" % self._t)
        self._took(self._lib.sim_step(self._sim, self._e, ctypes.byref(self._step)))
        return self._t

    def advance(self, t):
        """Steps until t exactly (at most t_end): the last ends there."""
        t = _set_value("t", t)
        if not (self._t < t <= self.t_end):
            raise UsageError("sim: advance(%r): not after t = %r, or past t_end = %r"
                             % (t, self._t, self.t_end))
        while self._t < t:
            self._took(self._lib.sim_advance(self._sim, self._e, t, ctypes.byref(self._step)))
        return self._t


class Linearization:
    """z' = A z + B u at a state: ``A`` (n x n), ``B`` (n x nu), ``states``
    (z's components: coordinates and ``name'`` velocities, a constrained
    model's independent ones), ``inputs``, and A's ``eigenvalues`` (complex,
    the largest real part first), as the command line's ``--csv`` has them.
    For an equilibrium also ``q`` (the coordinates found, by name),
    ``iterations`` and ``verdict`` (the command line's line on stability)."""

    def __init__(self, csv_text, text=""):
        A, B, eig = {}, {}, {}
        states, inputs = [], []
        for line in csv_text.splitlines()[1:]:
            kind, row, col, value = line.split(",")
            if kind == "eig":
                k = int(row)
                eig.setdefault(k, [0.0, 0.0])[0 if col == "re" else 1] = float(value)
                continue
            if row not in states:
                states.append(row)
            if kind == "A":
                A[row, col] = float(value)
            else:
                if col not in inputs:
                    inputs.append(col)
                B[row, col] = float(value)
        n = len(states)
        self.states, self.inputs = states, inputs
        self.A = np.array([[A.get((r, c), 0.0) for c in states] for r in states]).reshape(n, n)
        self.B = np.array([[B.get((r, c), 0.0) for c in inputs]
                           for r in states]).reshape(n, len(inputs))
        self.eigenvalues = np.array([complex(*eig[k]) for k in sorted(eig)])
        self.text = text
        self.q, self.iterations, self.verdict = {}, None, None
        lines = text.splitlines()
        for i, line in enumerate(lines):
            if "an equilibrium, found by" in line:
                self.iterations = int(line.split("found by")[1].split()[0])
                for item in lines[i + 1:]:
                    if not item.startswith("  ") or " = " not in item:
                        break
                    name, value = item.strip().split(" = ")
                    self.q[name] = float(value)
            if "stable" in line.split(":")[0]:
                self.verdict = line
        self.stable = None if self.verdict is None else not self.verdict.startswith("unstable")


class Model:
    """One model in its shared library (see :func:`load`)."""

    def __init__(self, path):
        self._lib = lib = Library(path)
        self.path = path
        self.name = lib.model_text("name")
        self.spec = lib.model_text("spec")
        self.form = lib.model_text("form")
        self.scene = lib.model_text("scene") or None  # None: the spec's unnamed `scene:`
        self.coordinates = lib.names("q")
        # the speeds' own names (a free joint's angular velocity), or the
        # coordinates' velocities name' where the speeds are their rates
        self.speeds = lib.names("v") or [q + "'" for q in self.coordinates]
        self.parameters = lib.names("p")
        self.inputs = lib.names("u")
        self.constraints = lib.names("c")
        self.outputs = lib.names("out")
        self.events = lib.names("event")
        # every body and particle, then every frame and point the spec names
        self.places = lib.names("place")
        self.extended = bool(lib.model_ext)
        self._sim = lib.sim_alloc(lib.model)
        if not self._sim:
            raise EomcError("%s: out of memory, or a model built for another runtime" % path)
        self._sim_u = None    # another simulator, for accel with inputs given
        self._sets = {}       # what set() set, in order: each run's --set
        nc = len(self.constraints)  # accel's check of its state, under the lock
        self._off, self._off_level = np.zeros(nc), (ctypes.c_int * nc)()
        self._off_e = as_doubles(self._off)
        self._lock = threading.Lock()

    def __del__(self):
        lib = getattr(self, "_lib", None)
        for s in (getattr(self, "_sim", None), getattr(self, "_sim_u", None)):
            if lib is not None and s:
                lib.sim_free(s)

    def __repr__(self):
        own = self.speeds != [q + "'" for q in self.coordinates]
        return "<eomc.Model %s: %d coordinates%s, form %s>" % (
            self.name, len(self.coordinates),
            " and %d speeds" % len(self.speeds) if own else "", self.form)

    def _error(self, sim):
        return self._lib.sim_error(sim).decode()

    # ---- parameters and accelerations, by the API ----

    def set(self, **values):
        """Set parameters, or inputs held constant from then on, by name.
        Unknown names, values that are not finite numbers and unphysical
        values (a negative mass, an impossible inertia) raise UsageError
        naming the value (eomc's message, with "did you mean"); nothing is
        set then."""
        values = {name: _set_value(name, v) for name, v in values.items()}
        with self._lock:
            trial = self._lib.sim_alloc(self._lib.model)
            try:
                for name, v in list(self._sets.items()) + list(values.items()):
                    if self._lib.sim_set(trial, name.encode(), v) != 0:
                        raise UsageError(self._error(trial))
                if self._lib.sim_check(trial) != 0:
                    raise UsageError(self._error(trial))
            finally:
                self._lib.sim_free(trial)
            for name, v in values.items():
                self._sets[name] = v
                for s in (self._sim, self._sim_u):
                    if s:
                        self._lib.sim_set(s, name.encode(), v)

    @property
    def params(self):
        """The parameters' current values, by name."""
        p = self._lib.sim_params(self._sim)
        return {name: p[k] for k, name in enumerate(self.parameters)}

    def initial(self):
        """The scene's initial state for the current parameters: (q, v), v
        the speeds (``speeds``: the coordinates' velocities, or a free
        body's own, fewer than its coordinates)."""
        q, v = np.zeros(len(self.coordinates)), np.zeros(len(self.speeds))
        with self._lock:
            self._lib.sim_initial(self._sim, as_doubles(q), as_doubles(v))
        return q, v

    def accel(self, q, v, u=None, t=0.0, multipliers=False, extended=False):
        """The speeds' rates v' at (t, q, v) (q'' where the speeds are the
        coordinates' velocities), with the inputs u held at these values
        (else the model's own); with multipliers=True, (v', lambda) for a
        constrained model.  A singular system raises NumericalFailure; a
        state off the holonomic or velocity constraints (a quaternion whose
        norm is not 1) gives an EomcWarning, as a run's start does.
        extended=True solves in the extended-precision twin (the reference
        solution's functions, long double on x86-64), rounded to doubles:
        the library built with it (``extended``)."""
        q, v = self._state("accel", q, v)
        nv = len(self.speeds)
        a = np.zeros(nv)
        with self._lock:
            sim = self._sim_with("accel", u)
            off = self._off_constraints(sim, float(t), q, v)
            if off:
                warnings.warn("%s: warning: accel: %s: q'' there is not that of a motion on "
                              "the constraints (run(init=..., assemble=True) projects a "
                              "state onto them)" % (self.name, off), EomcWarning,
                              stacklevel=2)
            if extended:
                if not self.extended:
                    raise UsageError("accel(extended=True): %s was built without its "
                                     "extended-precision twin (load(..., extended=True))"
                                     % self.name)
                x = np.concatenate([q, v])
                lam_x = np.zeros(max(len(self.constraints), 1))
                rc = self._lib.reference_accel(sim, self._lib.model_ext, float(t),
                                               as_doubles(x), as_doubles(a), as_doubles(lam_x))
            else:
                rc = self._lib.sim_accel(sim, float(t), as_doubles(q), as_doubles(v),
                                         as_doubles(a))
            if rc != 0:
                raise NumericalFailure(self._error(sim), float(t))
            lam = None
            if multipliers and extended:
                lam = lam_x[:len(self.constraints)].copy()
            elif multipliers:
                p = self._lib.sim_multipliers(sim)
                lam = np.array([p[k] for k in range(len(self.constraints))]) if p else np.zeros(0)
        return (a, lam) if multipliers else a

    def _sim_with(self, what, u):
        """The simulator to evaluate on (the lock held): the model's own, or
        with u given, another with the inputs held at u."""
        if u is None:
            return self._sim
        u = np.atleast_1d(np.asarray(u, dtype=np.float64))
        if u.shape != (len(self.inputs),):
            raise UsageError("%s: u needs %d entries (%s)" % (
                what, len(self.inputs), ", ".join(self.inputs) or "the model has no inputs"))
        if not self._sim_u:
            self._sim_u = self._lib.sim_alloc(self._lib.model)
            for name, val in self._sets.items():
                self._lib.sim_set(self._sim_u, name.encode(), val)
        for name, val in zip(self.inputs, u):
            self._lib.sim_set(self._sim_u, name.encode(), float(val))
        return self._sim_u

    def _state(self, what, q, v):
        n, nv = len(self.coordinates), len(self.speeds)
        q = np.ascontiguousarray(q, dtype=np.float64)
        v = np.zeros(nv) if v is None else np.ascontiguousarray(v, dtype=np.float64)
        if q.shape != (n,) or v.shape != (nv,):
            raise UsageError("%s: q needs %d entries (%s) and v %d (%s), not %s and %s"
                             % (what, n, ", ".join(self.coordinates), nv,
                                ", ".join(self.speeds), q.shape, v.shape))
        return q, v

    def _mass_bias(self, what, q, v, u, t):
        q, v = self._state(what, q, v)
        nv = len(self.speeds)
        M, h = np.zeros((nv, nv)), np.zeros(nv)
        with self._lock:
            sim = self._sim_with(what, u)
            if self._lib.sim_mass_bias(sim, float(t), as_doubles(q), as_doubles(v),
                                       as_doubles(M), as_doubles(h)) != 0:
                raise NumericalFailure(self._error(sim), float(t))
        return M, h

    def mass(self, q, t=0.0):
        """The mass matrix M(q), nv x nv (one row per speed): the motion is
        M v' + bias = 0 (a constrained model's: M v' + bias + B^T lambda = 0)."""
        return self._mass_bias("mass", q, None, None, t)[0]

    def bias(self, q, v, u=None, t=0.0):
        """h(q, v) - Q(q, v, u): everything of the motion but M v' (velocity
        terms, gravity, every force, the inputs'), so that the forward
        dynamics is M v' + bias = 0; u: the inputs held at these values
        (else the model's own)."""
        return self._mass_bias("bias", q, v, u, t)[1]

    def inverse(self, q, v, a, u=None, t=0.0):
        """The generalized forces tau = M a + bias that, added to the
        model's, make a the speeds' rates: 0 where a is the forward
        dynamics' answer (accel).  A constrained model's leaves out the
        constraints' forces: at its accel it is -B^T lambda, the force the
        constraints exert (accel(..., multipliers=True))."""
        M, h = self._mass_bias("inverse", q, v, u, t)
        a = np.ascontiguousarray(a, dtype=np.float64)
        if a.shape != (len(self.speeds),):
            raise UsageError("inverse: a needs %d entries (%s), not %s"
                             % (len(self.speeds), ", ".join(self.speeds), a.shape))
        return M @ a + h

    def accel_derivatives(self, q, v, u=None, t=0.0):
        """The derivatives of accel at any state, exact (the generated
        Jacobian, through the model's solve): (dv'/dq [nv x nq], dv'/dv
        [nv x nv], dv'/du [nv x nu]).  For a unit quaternion's four
        coordinates, the derivative along its sphere (the motion's)."""
        q, v = self._state("accel_derivatives", q, v)
        nq, nv, nu = len(self.coordinates), len(self.speeds), len(self.inputs)
        # one block, its three parts' addresses apart: one as_doubles, not three
        out = np.empty(nv * (nq + nv + nu))
        dq, dv = out[:nv * nq].reshape(nv, nq), out[nv * nq:nv * (nq + nv)].reshape(nv, nv)
        du = out[nv * (nq + nv):].reshape(nv, nu)
        base, size = as_doubles(out), out.itemsize
        with self._lock:
            sim = self._sim_with("accel_derivatives", u)
            if self._lib.sim_accel_derivatives(sim, float(t), as_doubles(q), as_doubles(v),
                                               base, base + size * nv * nq,
                                               base + size * nv * (nq + nv) if nu else None
                                               ) != 0:
                msg = self._error(sim)
                if "Jacobian" in msg and "built without" in msg:
                    raise UsageError(msg)
                raise NumericalFailure(msg, float(t))
        return dq, dv, du

    def _place(self, what, name, q):
        """(index, has axes, q as doubles) of the place called name."""
        axes = ctypes.c_int()
        k = self._lib.model_place(self._lib.model, str(name).encode(), ctypes.byref(axes))
        if k < 0:
            near = difflib.get_close_matches(str(name), self.places, 1)
            raise UsageError("%s: %s has no place '%s'%s (its places: its bodies, particles, "
                             "frames and points: %s)" % (
                                 what, self.name, name,
                                 " (did you mean '%s'?)" % near[0] if near else "",
                                 ", ".join(self.places) or "none"))
        q = np.ascontiguousarray(q, dtype=np.float64)
        if q.shape != (len(self.coordinates),):
            raise UsageError("%s: q needs %d entries (%s), not %s" % (
                what, len(self.coordinates), ", ".join(self.coordinates), q.shape))
        return k, bool(axes.value), q

    def position(self, name, q, t=0.0):
        """The world position [3] of a place at (t, q): a body's centre of
        mass, a particle, a frame's origin or a point (``places``)."""
        k, _, q = self._place("position", name, q)
        pos = np.zeros(3)
        with self._lock:
            if self._lib.sim_place(self._sim, k, float(t), as_doubles(q), as_doubles(pos),
                                   None) != 0:
                raise NumericalFailure(self._error(self._sim), float(t))
        return pos

    def rotation(self, name, q, t=0.0):
        """The rotation [3 x 3] of a body's or frame's axes at (t, q): its
        columns are the axes in world components (R maps the place's
        components to the world's).  A point or particle has none
        (UsageError)."""
        k, axes, q = self._place("rotation", name, q)
        R = np.zeros((3, 3))
        with self._lock:
            rc = self._lib.sim_place(self._sim, k, float(t), as_doubles(q), None, as_doubles(R))
            if rc != 0:
                msg = self._error(self._sim)
                # EOMC_EUSAGE (2): asked of what has no axes or out of range
                raise (UsageError("rotation: " + msg) if rc == 2
                       else NumericalFailure(msg, float(t)))
        return R

    def jacobian(self, name, q, t=0.0):
        """The velocity Jacobian of a place at (t, q), exact, in world
        components: 3 x nv for a point or particle (its velocity is J v),
        6 x nv for a body or frame, its velocity's rows over its angular
        velocity's (as Pinocchio's LOCAL_WORLD_ALIGNED).  A body's velocity
        is its centre of mass's, a frame's its origin's.  What time alone
        moves (a driven frame) is left out."""
        k, axes, q = self._place("jacobian", name, q)
        nv = len(self.speeds)
        J = np.zeros((6 if axes else 3, nv))
        with self._lock:
            if self._lib.sim_place_jacobian(self._sim, k, float(t), as_doubles(q),
                                            as_doubles(J[:3]),
                                            as_doubles(J[3:]) if axes else None) != 0:
                raise NumericalFailure(self._error(self._sim), float(t))
        return J

    def _off_constraints(self, sim, t, q, v):
        """The constraints (q, v) is off, worst first, as `eomc run` says of
        an initial state off them ("the state is off the constraint rod
        (positions: its residual is 0.12 of the size of its terms)"), or
        "": the runtime's eomc_sim_inconsistencies, each constraint's
        residual relative to its terms, above EOMC_INCONSISTENT."""
        if not self.constraints:
            return ""
        e, level = self._off, self._off_level
        if not self._lib.sim_inconsistencies(sim, t, as_doubles(q), as_doubles(v),
                                             self._off_e, level) > INCONSISTENT:
            return ""
        off = [k for k in np.argsort(-e, kind="stable") if e[k] > INCONSISTENT]
        said = ["%s (%s: %s%.2g%s)" % (self.constraints[k],
                                       "velocities" if level[k] else "positions",
                                       "" if j else "its residual is ", e[k],
                                       "" if j else " of the size of its terms")
                for j, k in enumerate(off)]
        if len(off) == 1:
            return "the state is off the constraint " + said[0]
        return "the state is off %d constraints, worst first: %s" % (len(off), ", ".join(said))

    def sim(self, init=None, t0=None, t_end=None, method=None, rtol=None, atol=None,
            fixed_step=None, max_steps=None):
        """A :class:`Sim`: one motion stepped from Python, from the scene's
        initial state (with init's values), with the scene's method and
        tolerances unless given; t_end bounds it (the scene's)."""
        return Sim(self, init, t0, t_end, method, rtol, atol, fixed_step, max_steps)

    # ---- the simulator's tasks, by its command line ----

    def _call(self, options, stacklevel=3, extra=None):
        argv = [self.name]
        for name, v in self._sets.items():
            argv += ["--set", "%s=%r" % (name, v)]
        argv += options
        status, out, err = self._lib.main(argv, extra)
        if status == 2:  # a usage error, in the keywords' terms
            err = as_keywords(err)
        warn_lines(err, stacklevel=stacklevel + 1)
        return status, out, err

    def run(self, t_end=None, dt=None, method=None, rtol=None, init=None, controller=None,
            period=None, **options):
        """Integrate the scene (its t_end, dt, method and tolerances unless
        given; init: {coordinate or speed: value}, a speed by its name in
        ``speeds``, "x'" or "root_wx") and return the rows as
        a :class:`Run`.  Other keywords are simulator options (``atol``,
        ``t0``, ``fixed_step``, ``max_steps``, ``stabilize``, ``assemble``,
        ``stats``, ``summary``, ``error``, ``sweep``, ...); ``error=True``
        (or ``reference``, ``errors``) implies ``stats=True``, so that ``.stats``
        has ``error_end``, ``error_max`` and ``reference_error``.  A run
        that fails raises NumericalFailure, with the rows computed before
        it.

        controller: f(t, q, v) giving the inputs, a sequence in ``inputs``
        order or a dict by name (an input a dict leaves out keeps its own
        value there); with ``period``, sampled at t0 + k period and held
        between (the steps end at every sample), else continuous, inside
        every right-hand side.  It must be a function of (t, q, v) alone:
        ``error=True`` calls it again at the same instants for the
        reference.  What goes wrong in it raises ControllerError naming the
        time, the rows before it kept.

        The rows come from the run's memory as numbers, the same doubles
        ``eomc run`` prints, so equal to its CSV to the bit."""
        kw = dict(t_end=t_end, dt=dt, method=method, rtol=rtol, init=init)
        kw.update(options)
        if kw.get("error") or kw.get("reference") or kw.get("errors"):  # into .stats
            kw["stats"] = True
        if period is not None and controller is None:
            raise UsageError("run: period is a controller's sampling period, and no "
                             "controller was given")
        if controller is not None and not callable(controller):
            raise UsageError("run: controller must be a function f(t, q, v), not %r"
                             % (controller,))
        ctrl = _Controller(self, controller) if controller is not None else None
        extra = MainExtra(rows_in_memory=1)
        if ctrl is not None:
            p = 0.0 if period is None else _set_value("period", period)
            if p <= 0 and period is not None:
                raise UsageError("run: period must be positive, not %r (leave it out for a "
                                 "continuous controller)" % (period,))
            extra.controller, extra.period = ctrl.cfn, p
        status, out, err = self._call(_options(kw), extra=extra)
        names, rows = self._lib.take_rows(extra)
        if names:
            columns = names
            data = {name: np.ascontiguousarray(rows[:, j]) for j, name in enumerate(names)}
        else:  # a sweep's rows, or no run
            columns, data = _table(out) if status in (0, 3) else ([], {})
        r = Run(columns, data, err, out if names else "")
        if ctrl is not None and ctrl.error is not None:
            ctrl.raise_after(r)
        raise_for(status, err, r)
        return r

    def _with_csv(self, flag, options, name="out.csv", extra=()):
        with tempfile.TemporaryDirectory(prefix="eomc-py-") as d:
            path = os.path.join(d, name)
            status, out, err = self._call(_options(options) + list(extra) + [flag, path],
                                          stacklevel=4)
            raise_for(status, err)
            with open(path) as f:
                return f.read(), out, err

    def linearize(self, init=None, **options):
        """A and B at the initial state (or init), and A's eigenvalues: a
        :class:`Linearization` (the command line's --linearize)."""
        options.update(init=init, linearize=True)
        csv, out, _ = self._with_csv("--csv", options)
        return Linearization(csv, out)

    def equilibrium(self, init=None, **options):
        """An equilibrium by Newton's method from the initial coordinates (or
        init), with its linearization (``.q``, ``.A``, ``.eigenvalues``,
        ``.stable``): the command line's --equilibrium."""
        options.update(init=init, equilibrium=True)
        csv, out, _ = self._with_csv("--csv", options)
        return Linearization(csv, out)

    def accuracy(self, methods=None, tolerances=None, **options):
        """The work-precision report (``eomc accuracy``): one row per run,
        by the report's CSV columns; ``.text`` is the printed table."""
        options.update(methods=methods, tolerances=tolerances, work_precision=True)
        csv, out, err = self._with_csv("--csv", options)
        columns, data = _table(csv)
        return Run(columns, data, err, out)

    def reference(self, init=None, **options):
        """The reference solution the accuracy report measures against, at
        the run's output times: a :class:`Run` with t, coordinates and
        velocities (computed in extended precision; the library needs its
        twin, which a small model always has and a large one gets from
        ``load(..., extended=True)``)."""
        options.update(init=init)
        # the run beside it is not wanted: its rows go nowhere
        csv, out, err = self._with_csv("--reference-out", options, "reference.csv",
                                       ["-o", os.devnull])
        columns, data = _table(csv)
        return Run(columns, data, err)
