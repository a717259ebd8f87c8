"""The runtime's C API (runtime/include/eomc.h) in a model's shared library, through ctypes.

``eomc build --shared`` makes one library holding the model, its
extended-precision twin when built, and the whole runtime; it names the
model ``eomc_shared_model()`` whatever the spec calls it.  Every call here
goes to that library, so two models loaded side by side share nothing but
the process (GSL's error handler, which is turned off once: eomc checks
every status itself and must never abort Python).  ctypes lets go of the
GIL for each foreign call, so runs in threads proceed at once.
"""

import ctypes

import numpy as np

_c_double_p = ctypes.POINTER(ctypes.c_double)

# eomc_controller_fn: (ctx, t, q, v, u) -> status; the arrays as addresses
# (plain ints: cheaper to take than pointer objects, at every call)
CONTROLLER = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_double, ctypes.c_void_p,
                              ctypes.c_void_p, ctypes.c_void_p)


class RunOpts(ctypes.Structure):
    """eomc_run_opts."""
    _fields_ = [("t0", ctypes.c_double), ("t_end", ctypes.c_double), ("dt", ctypes.c_double),
                ("method", ctypes.c_char_p), ("rtol", ctypes.c_double),
                ("atol", ctypes.c_double), ("h_fixed", ctypes.c_double),
                ("max_steps", ctypes.c_long), ("on_progress", ctypes.c_void_p),
                ("progress_ctx", ctypes.c_void_p), ("on_event", ctypes.c_void_p),
                ("event_ctx", ctypes.c_void_p)]


class Step(ctypes.Structure):
    """eomc_step: what one accepted step covered."""
    _fields_ = [("nx", ctypes.c_int), ("t0", ctypes.c_double), ("t1", ctypes.c_double),
                ("x0", _c_double_p), ("f0", _c_double_p), ("x1", _c_double_p),
                ("f1", _c_double_p), ("event", ctypes.c_int), ("last", ctypes.c_int),
                ("series", ctypes.c_void_p), ("model", ctypes.c_void_p)]


class MainExtra(ctypes.Structure):
    """eomc_main_extra: a controller for the run, its rows in memory."""
    _fields_ = [("controller", CONTROLLER), ("controller_ctx", ctypes.c_void_p),
                ("period", ctypes.c_double), ("drives", ctypes.c_void_p),
                ("rows_in_memory", ctypes.c_int), ("rows", _c_double_p),
                ("nrows", ctypes.c_long), ("ncols", ctypes.c_int),
                ("columns", ctypes.c_void_p)]

# EOMC_INCONSISTENT of runtime/include/eomc.h: a state whose constraint is
# off by more than this share of its terms is said to be off it (the
# tests read the header to keep the two the same)
INCONSISTENT = 1e-8


class Library:
    """One model's library: its functions with their C signatures."""

    def __init__(self, path):
        self.path = path
        lib = ctypes.CDLL(path)
        self.lib = lib

        def fn(name, restype, *argtypes):
            f = getattr(lib, name)
            f.restype, f.argtypes = restype, list(argtypes)
            return f

        vp, cp, i, d = ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_double
        D = vp  # a double *: an array's address (as_doubles) or None
        self.model = fn("eomc_shared_model", vp)()
        self.model_ext = fn("eomc_shared_model_ext", vp)()  # None: built without
        self.count = fn("eomc_model_count", i, vp, cp)
        self.name = fn("eomc_model_name", cp, vp, cp, i)
        self.text = fn("eomc_model_text", cp, vp, cp)
        self.sim_alloc = fn("eomc_sim_alloc", vp, vp)
        self.sim_free = fn("eomc_sim_free", None, vp)
        self.sim_set = fn("eomc_sim_set", i, vp, cp, d)
        self.sim_check = fn("eomc_sim_check", i, vp)
        self.sim_params = fn("eomc_sim_params", _c_double_p, vp)
        self.sim_initial = fn("eomc_sim_initial", None, vp, D, D)
        self.sim_accel = fn("eomc_sim_accel", i, vp, d, D, D, D)
        self.sim_multipliers = fn("eomc_sim_multipliers", _c_double_p, vp)
        self.reference_accel = fn("eomc_reference_accel", i, vp, vp, d, D, D, D)
        self.sim_mass_bias = fn("eomc_sim_mass_bias", i, vp, d, D, D, D, D)
        self.sim_accel_derivatives = fn("eomc_sim_accel_derivatives", i, vp, d, D, D, D, D, D)
        self.model_place = fn("eomc_model_place", i, vp, cp, ctypes.POINTER(i))
        self.sim_place = fn("eomc_sim_place", i, vp, i, d, D, D, D)
        self.sim_place_jacobian = fn("eomc_sim_place_jacobian", i, vp, i, d, D, D, D)
        self.sim_inconsistencies = fn("eomc_sim_inconsistencies", d, vp, d, D, D, D,
                                      ctypes.POINTER(i))
        self.sim_error = fn("eomc_sim_error", cp, vp)
        self.main_mem = fn("eomc_main_mem", i, i, ctypes.POINTER(cp), vp, vp,
                           ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_size_t),
                           ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_size_t))
        self.main_with = fn("eomc_main_with", i, i, ctypes.POINTER(cp), vp, vp,
                            ctypes.POINTER(MainExtra),
                            ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_size_t),
                            ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_size_t))
        self.free = fn("eomc_free", None, vp)
        self.run_defaults = fn("eomc_run_defaults", RunOpts, vp)
        self.evolve_alloc = fn("eomc_evolve_alloc", vp, vp, ctypes.POINTER(RunOpts), D)
        self.evolve_free = fn("eomc_evolve_free", None, vp)
        self.sim_step = fn("eomc_sim_step", i, vp, vp, ctypes.POINTER(Step))
        self.sim_advance = fn("eomc_sim_advance", i, vp, vp, d, ctypes.POINTER(Step))
        self.evolve_restart = fn("eomc_evolve_restart", i, vp, vp, D)
        self.sim_inputs = fn("eomc_sim_inputs", None, vp, d, D)
        # eomc reports GSL's errors as its own statuses; GSL's default
        # handler would abort the interpreter (runtime/include/eomc.h)
        fn("gsl_set_error_handler_off", vp)()

    def names(self, kind):
        n = self.count(self.model, kind.encode())
        return [self.name(self.model, kind.encode(), k).decode() for k in range(n)]

    def model_text(self, what):
        s = self.text(self.model, what.encode())
        return s.decode() if s is not None else None

    def main(self, argv, extra=None):
        """The simulator's command line on argv (argv[0] names the model in
        messages): (exit status, stdout text, stderr text).  extra: a
        MainExtra (a controller, rows in memory), filled in by the call."""
        args = (ctypes.c_char_p * (len(argv) + 1))(*[a.encode() for a in argv], None)
        out, err = ctypes.c_void_p(), ctypes.c_void_p()
        nout, nerr = ctypes.c_size_t(), ctypes.c_size_t()
        if extra is None:
            status = self.main_mem(len(argv), args, self.model, self.model_ext,
                                   ctypes.byref(out), ctypes.byref(nout),
                                   ctypes.byref(err), ctypes.byref(nerr))
        else:
            status = self.main_with(len(argv), args, self.model, self.model_ext,
                                    ctypes.byref(extra), ctypes.byref(out), ctypes.byref(nout),
                                    ctypes.byref(err), ctypes.byref(nerr))
        try:
            o = ctypes.string_at(out, nout.value).decode() if out.value else ""
            e = ctypes.string_at(err, nerr.value).decode() if err.value else ""
        finally:
            self.free(out)
            self.free(err)
        return status, o, e

    def take_rows(self, extra):
        """The rows a run kept in memory (MainExtra), as (column names, a
        float64 array rows x columns), the C buffers freed."""
        names = (ctypes.string_at(extra.columns).decode().split(",")
                 if extra.columns else [])
        if extra.rows and extra.nrows > 0:
            data = np.ctypeslib.as_array(extra.rows, shape=(extra.nrows, extra.ncols)).copy()
        else:
            data = np.zeros((0, len(names)))
        self.free(ctypes.cast(extra.rows, ctypes.c_void_p))
        self.free(extra.columns)
        extra.rows, extra.columns = None, None
        return names, data


def as_doubles(a):
    """The address of a contiguous float64 numpy array's data, for a
    double * argument (declared void *): 0.8 us, where a ctypes pointer
    (data_as) costs 2.3, five times in one accel_derivatives.  It does not
    keep the array alive: the caller holds it through the call."""
    return a.ctypes.data
