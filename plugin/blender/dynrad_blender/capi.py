"""ctypes binding of libdynrad.so (plugin/capi/include/dynrad/dynrad.h).

Plain Python with no Blender import, so it can be used and tested on its own. Arrays
go through the standard library's `array` module (Debian's Blender has no numpy).
"""

import array
import ctypes
import ctypes.util
import json
import os

ABI_VERSION = 1  # DYNRAD_ABI_VERSION of the header this binding follows

STATUS_NAMES = {
    0: "DYNRAD_OK",
    1: "DYNRAD_STOPPED",
    -1: "DYNRAD_INVALID_ARGUMENT",
    -2: "DYNRAD_INVALID_INPUT",
    -3: "DYNRAD_NO_EMITTER",
    -4: "DYNRAD_BUFFER_TOO_SMALL",
    -5: "DYNRAD_OUT_OF_MEMORY",
    -6: "DYNRAD_INTERNAL_ERROR",
    -7: "DYNRAD_OUTPUT_ERROR",
}
OK, STOPPED = 0, 1
STOP_REASONS = ("converged", "iterations", "time limit", "cancelled", "error target", "error floor")


class DynradError(RuntimeError):
    """A failed call: `status` is the library's status name, the message its text."""

    def __init__(self, status, message):
        super().__init__(message)
        self.status = STATUS_NAMES.get(status, str(status))


class Material(ctypes.Structure):
    _fields_ = [
        ("reflectance", ctypes.c_double * 3),
        ("emission", ctypes.c_double * 3),
        ("name", ctypes.c_char_p),
    ]


class Report(ctypes.Structure):
    _fields_ = [
        ("shots", ctypes.c_uint64),
        ("energy_transfers", ctypes.c_uint64),
        ("patch_element_transfers", ctypes.c_uint64),
        ("visibility_rays", ctypes.c_uint64),
        ("patches", ctypes.c_uint64),
        ("elements", ctypes.c_uint64),
        ("seconds", ctypes.c_double),
        ("unshot_fraction", ctypes.c_double),
        ("exposure", ctypes.c_double),
        ("patch_size", ctypes.c_double),
        ("emitted", ctypes.c_double * 3),
        ("absorbed", ctypes.c_double * 3),
        ("escaped", ctypes.c_double * 3),
        ("stopped_by", ctypes.c_int),
        ("estimated_error", ctypes.c_double),
    ]


PROGRESS_FN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_uint64, ctypes.c_double, ctypes.c_void_p)

_c_double_p = ctypes.POINTER(ctypes.c_double)
_c_uint32_p = ctypes.POINTER(ctypes.c_uint32)


def library_candidates(explicit_path=""):
    """Where to look for libdynrad.so, in order: the given path (the add-on's
    preference), $DYNRAD_LIBRARY, next to this file, the system's library path."""
    candidates = []
    if explicit_path:
        candidates.append(explicit_path)
    if os.environ.get("DYNRAD_LIBRARY"):
        candidates.append(os.environ["DYNRAD_LIBRARY"])
    candidates.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), "libdynrad.so"))
    found = ctypes.util.find_library("dynrad")
    if found:
        candidates.append(found)
    return candidates


class Library:
    """The loaded library with its function signatures declared."""

    def __init__(self, explicit_path=""):
        tried = []
        self.path = None
        for candidate in library_candidates(explicit_path):
            if os.path.sep in candidate and not os.path.exists(candidate):
                tried.append(candidate + " (no such file)")
                continue
            try:
                self._lib = ctypes.CDLL(candidate)
                self.path = candidate
                break
            except OSError as error:
                tried.append("%s (%s)" % (candidate, error))
        if self.path is None:
            raise DynradError(
                -1,
                "libdynrad.so not found. Build dynrad (it is build/plugin/capi/libdynrad.so) and set the "
                "add-on's library path, or $DYNRAD_LIBRARY, or copy it next to the add-on. Tried: "
                + "; ".join(tried),
            )
        self._declare()
        if self._lib.dynrad_abi_version() != ABI_VERSION:
            raise DynradError(
                -1,
                "%s has ABI version %d, this add-on needs %d: use the add-on from the same dynrad build."
                % (self.path, self._lib.dynrad_abi_version(), ABI_VERSION),
            )

    def _declare(self):
        lib = self._lib
        status = ctypes.c_int
        size = ctypes.c_size_t
        handle = ctypes.c_void_p
        signatures = {
            "dynrad_version": (ctypes.c_char_p, []),
            "dynrad_abi_version": (ctypes.c_int, []),
            "dynrad_last_error": (ctypes.c_char_p, []),
            "dynrad_scene_create": (
                status,
                [_c_double_p, size, _c_uint32_p, _c_uint32_p, size, _c_uint32_p, ctypes.POINTER(Material), size,
                 ctypes.POINTER(handle)],
            ),
            "dynrad_scene_load": (status, [ctypes.c_char_p, ctypes.POINTER(handle)]),
            "dynrad_scene_destroy": (None, [handle]),
            "dynrad_options_create": (status, [ctypes.POINTER(handle)]),
            "dynrad_options_destroy": (None, [handle]),
            "dynrad_options_set_method": (status, [handle, ctypes.c_char_p]),
            "dynrad_options_set_quality": (status, [handle, ctypes.c_char_p]),
            "dynrad_options_set_max_level": (status, [handle, ctypes.c_int]),
            "dynrad_options_set_patch_size": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_converge": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_iterations": (status, [handle, ctypes.c_uint64]),
            "dynrad_options_set_time_limit": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_threads": (status, [handle, ctypes.c_int]),
            "dynrad_options_set_seed": (status, [handle, ctypes.c_uint64]),
            "dynrad_options_set_threshold": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_exposure": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_ambient": (status, [handle, ctypes.c_int]),
            "dynrad_options_set_simplify": (status, [handle, ctypes.c_int]),
            "dynrad_options_set_oracle": (status, [handle, ctypes.c_char_p]),
            "dynrad_options_set_oracle_threshold": (status, [handle, ctypes.c_char_p, ctypes.c_double]),
            "dynrad_options_set_max_elements": (status, [handle, ctypes.c_uint64]),
            "dynrad_options_set_overshoot": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_negligible_share": (status, [handle, ctypes.c_double]),
            "dynrad_options_set_shaped_senders": (status, [handle, ctypes.c_int]),
            "dynrad_solve": (
                status,
                [handle, handle, PROGRESS_FN, ctypes.c_void_p, ctypes.POINTER(ctypes.c_int), ctypes.POINTER(handle)],
            ),
            "dynrad_result_destroy": (None, [handle]),
            "dynrad_result_vertex_count": (size, [handle]),
            "dynrad_result_triangle_count": (size, [handle]),
            "dynrad_result_positions": (status, [handle, _c_double_p, size]),
            "dynrad_result_triangles": (status, [handle, _c_uint32_p, size]),
            "dynrad_result_triangle_materials": (status, [handle, _c_uint32_p, size]),
            "dynrad_result_radiosity": (status, [handle, ctypes.POINTER(ctypes.c_float), size]),
            "dynrad_result_display": (status, [handle, ctypes.POINTER(ctypes.c_uint8), size]),
            "dynrad_result_report": (status, [handle, ctypes.POINTER(Report)]),
            "dynrad_result_illuminance": (status, [handle, ctypes.POINTER(ctypes.c_float), size]),
            "dynrad_result_report_json": (ctypes.c_char_p, [handle]),
            "dynrad_result_grid_count": (size, [handle]),
            "dynrad_result_grid_name": (ctypes.c_char_p, [handle, size]),
            "dynrad_result_grid_point_count": (size, [handle, size]),
            "dynrad_result_grid_points": (status, [handle, size, _c_double_p, size]),
            "dynrad_result_write_report": (status, [handle, ctypes.c_char_p]),
            "dynrad_false_colour": (status, [ctypes.c_double, ctypes.POINTER(ctypes.c_uint8)]),
        }
        for name, (restype, argtypes) in signatures.items():
            if not hasattr(lib, name):
                raise DynradError(-1, "%s has no %s: it is older than this add-on; use the library of the same "
                                      "dynrad build." % (self.path, name))
            function = getattr(lib, name)
            function.restype = restype
            function.argtypes = argtypes

    def version(self):
        return self._lib.dynrad_version().decode()

    def check(self, status):
        """Raises DynradError for a failure status; returns the status otherwise."""
        if status < 0:
            raise DynradError(status, self._lib.dynrad_last_error().decode(errors="replace"))
        return status

    def __getattr__(self, name):
        return getattr(self._lib, name)


def _pointer(values, typecode, ctype):
    """A ctypes pointer into an array.array (which must stay alive during the call)."""
    buffer = values if isinstance(values, array.array) and values.typecode == typecode else array.array(typecode, values)
    return buffer, (ctype * len(buffer)).from_buffer(buffer) if len(buffer) else None


class Result:
    """What a solve returns, copied out of the library into array.array buffers: the
    refined mesh with per-vertex radiosity, display colours and illuminance, the report
    (dict, and `report_json`: the library's JSON report parsed) and per grid of a scene
    file its name and points (`grids`: list of (name, array of x y z E))."""

    def __init__(self, library, handle, stopped):
        count_v = library.dynrad_result_vertex_count(handle)
        count_t = library.dynrad_result_triangle_count(handle)
        self.positions = array.array("d", bytes(8 * 3 * count_v))
        self.triangles = array.array("I", bytes(4 * 3 * count_t))
        self.triangle_materials = array.array("I", bytes(4 * count_t))
        self.radiosity = array.array("f", bytes(4 * 3 * count_v))
        self.display = array.array("B", bytes(3 * count_v))
        for function, buffer, ctype, count in (
            (library.dynrad_result_positions, self.positions, ctypes.c_double, count_v),
            (library.dynrad_result_triangles, self.triangles, ctypes.c_uint32, count_t),
            (library.dynrad_result_triangle_materials, self.triangle_materials, ctypes.c_uint32, count_t),
            (library.dynrad_result_radiosity, self.radiosity, ctypes.c_float, count_v),
            (library.dynrad_result_display, self.display, ctypes.c_uint8, count_v),
        ):
            if count:
                library.check(function(handle, (ctype * len(buffer)).from_buffer(buffer), count))
        self.illuminance = array.array("f", bytes(4 * count_v))
        if count_v:
            library.check(library.dynrad_result_illuminance(
                handle, (ctypes.c_float * count_v).from_buffer(self.illuminance), count_v))
        self.report_json = json.loads(library.dynrad_result_report_json(handle).decode() or "{}")
        self.grids = []
        for grid in range(library.dynrad_result_grid_count(handle)):
            count = library.dynrad_result_grid_point_count(handle, grid)
            points = array.array("d", bytes(8 * 4 * count))
            if count:
                library.check(library.dynrad_result_grid_points(
                    handle, grid, (ctypes.c_double * len(points)).from_buffer(points), count))
            self.grids.append((library.dynrad_result_grid_name(handle, grid).decode(), points))
        report = Report()
        library.check(library.dynrad_result_report(handle, ctypes.byref(report)))
        self.report = {name: getattr(report, name) for name, _ in Report._fields_}
        for name in ("emitted", "absorbed", "escaped"):
            self.report[name] = list(self.report[name])
        self.report["stopped_by"] = STOP_REASONS[report.stopped_by]
        self.stopped = stopped

    @property
    def vertex_count(self):
        return len(self.positions) // 3

    @property
    def triangle_count(self):
        return len(self.triangles) // 3


# The names dynrad_options_set_oracle_threshold takes.
ORACLE_THRESHOLDS = ("cumulated_gradient", "current_gradient", "current_ratio", "pushdown_error", "pushdown_floor",
                     "pushdown_ambient")


def false_colour(library, t):
    """The report's false-colour scale at t in [0, 1]: (r, g, b) bytes, sRGB."""
    rgb = (ctypes.c_uint8 * 3)()
    library.check(library.dynrad_false_colour(float(t), rgb))
    return tuple(rgb)


def _apply_options(library, c_options, options):
    for name, value in options.items():
        if name in ORACLE_THRESHOLDS:
            library.check(library.dynrad_options_set_oracle_threshold(c_options, name.encode(), float(value)))
            continue
        setter = getattr(library, "dynrad_options_set_" + name, None)
        if setter is None:
            raise DynradError(-1, "unknown option '%s'" % name)
        library.check(setter(c_options, value.encode() if isinstance(value, str) else value))


def _solve_scene(library, scene, options, progress, cancel, report_path=None):
    """Solves `scene` (a dynrad_scene handle, destroyed here whatever happens) with
    `options`; with `report_path`, writes the HTML report before the result is released.
    Returns a Result."""
    c_options = ctypes.c_void_p()
    result = ctypes.c_void_p()
    try:
        library.check(library.dynrad_options_create(ctypes.byref(c_options)))
        _apply_options(library, c_options, options)

        def on_progress(shot, unshot, _user):
            try:
                return 1 if progress and progress(shot, unshot) else 0
            except Exception:  # an exception cannot cross C; stop the solve instead
                return 1

        callback = PROGRESS_FN(on_progress)
        cancel_pointer = ctypes.pointer(cancel) if cancel is not None else None
        status = library.check(library.dynrad_solve(scene, c_options, callback, None, cancel_pointer,
                                                    ctypes.byref(result)))
        if report_path:
            library.check(library.dynrad_result_write_report(result, report_path.encode()))
        return Result(library, result, status == STOPPED)
    finally:
        library.dynrad_result_destroy(result)
        library.dynrad_options_destroy(c_options)
        library.dynrad_scene_destroy(scene)


def solve_file(library, path, options, report_path=None, progress=None, cancel=None):
    """Loads a scene file (dynrad_scene_load: as `dynrad solve` reads it) and solves it
    with `options` (as for solve()). With `report_path`, also writes the HTML lighting
    report there (dynrad_result_write_report), with its pictures beside it, before the
    result is released. Returns a Result."""
    scene = ctypes.c_void_p()
    library.check(library.dynrad_scene_load(path.encode(), ctypes.byref(scene)))
    return _solve_scene(library, scene, options, progress, cancel, report_path)


def solve(library, positions, polygon_sizes, polygon_indices, polygon_materials, materials, options,
          progress=None, cancel=None):
    """Builds a scene and solves it.

    positions: flat x y z sequence; polygon_sizes, polygon_indices, polygon_materials as
    in dynrad_scene_create; materials: (name, reflectance rgb, emission rgb) tuples;
    options: dict of setter names (dynrad_options_set_NAME: method, quality, max_level, patch_size,
    converge, iterations, time_limit, threads, seed, threshold, oracle, max_elements,
    overshoot, negligible_share, shaped_senders, ambient, simplify, exposure) or names of
    dynrad_options_set_oracle_threshold (ORACLE_THRESHOLDS), applied in the dict's order
    (set oracle before cumulated_gradient: it picks whose gradient that is);
    progress(shot, unshot) returning
    True stops the solve; cancel: a ctypes.c_int another thread may set to 1.
    Returns a Result (result.stopped tells whether it was stopped early)."""
    keep = []

    def pointer(values, typecode, ctype):
        buffer, ptr = _pointer(values, typecode, ctype)
        keep.append(buffer)
        return ptr

    c_materials = (Material * len(materials))()
    for slot, (name, reflectance, emission) in zip(c_materials, materials):
        slot.reflectance[:] = [float(x) for x in reflectance]
        slot.emission[:] = [float(x) for x in emission]
        slot.name = name.encode()
    scene = ctypes.c_void_p()
    library.check(
        library.dynrad_scene_create(
            pointer(positions, "d", ctypes.c_double), len(positions) // 3,
            pointer(polygon_indices, "I", ctypes.c_uint32), pointer(polygon_sizes, "I", ctypes.c_uint32),
            len(polygon_sizes), pointer(polygon_materials, "I", ctypes.c_uint32),
            c_materials, len(materials), ctypes.byref(scene)))
    return _solve_scene(library, scene, options, progress, cancel)
