/* dynrad.h: the dynrad radiosity engine through a C interface.
 *
 * Purpose: light a polygon model given as plain arrays and read back the refined mesh
 * with per-vertex radiosity, from any language that can call C (Python ctypes, C#,
 * host applications' plug-ins).
 *
 * Conventions, for every function:
 * - Handles (dynrad_scene, dynrad_options, dynrad_result) are opaque; each has a
 *   create and a destroy function. destroy accepts NULL.
 * - Buffers belong to the caller. Results are copied out in two steps: ask for a size
 *   (dynrad_result_vertex_count, dynrad_result_triangle_count), allocate, then copy.
 *   Every copy function takes the capacity of the buffer, in elements (vertices or
 *   triangles), and returns DYNRAD_BUFFER_TOO_SMALL without writing when it is short.
 * - Functions that can fail return a dynrad_status. On failure, dynrad_last_error()
 *   gives a message for people (naming the polygon, vertex or material at fault and
 *   what to do); it is per thread and valid until the next dynrad call on that thread.
 *   No C++ exception ever leaves the library.
 * - Units: emission is radiant exitance (W/m^2 leaving the front side); reflectance
 *   is diffuse albedo per channel, linear, in [0, 1); radiosity comes back in W/m^2.
 *   The library is strict, as `dynrad --strict` is: a reflectance of 1 or more is
 *   DYNRAD_INVALID_INPUT naming the material, never lowered behind the caller's back
 *   (the command line's file readers lower it to 0.95 with a warning). A caller that
 *   takes colours from users clamps them itself; the Blender add-on clamps to 0.95.
 *   Lengths are in any unit: radiosity does not depend on it.
 * - A polygon's front is the side from which its corners run counter-clockwise. Only
 *   the front emits and reflects.
 * - The library is thread-safe for distinct handles. One scene may be solved from
 *   several threads at once.
 */
#ifndef DYNRAD_DYNRAD_H
#define DYNRAD_DYNRAD_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && defined(DYNRAD_BUILDING_LIBRARY)
#define DYNRAD_API __declspec(dllexport)
#elif defined(_WIN32)
#define DYNRAD_API __declspec(dllimport)
#elif defined(__GNUC__)
#define DYNRAD_API __attribute__((visibility("default")))
#else
#define DYNRAD_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* The layout of the structs below; dynrad_abi_version() must return the same. */
#define DYNRAD_ABI_VERSION 1

typedef enum dynrad_status {
  DYNRAD_OK = 0,
  /* dynrad_solve only: the caller stopped the solve (progress callback or cancel
   * flag). The result is valid and holds the solution so far. */
  DYNRAD_STOPPED = 1,
  DYNRAD_INVALID_ARGUMENT = -1, /* a NULL handle or pointer, an unknown name, a value out of range */
  DYNRAD_INVALID_INPUT = -2,    /* scene arrays: bad index, non-finite number, unphysical material */
  DYNRAD_NO_EMITTER = -3,       /* no polygon emits light: everything would be black */
  DYNRAD_BUFFER_TOO_SMALL = -4, /* a copy function's capacity is below the size query's answer */
  DYNRAD_OUT_OF_MEMORY = -5,
  DYNRAD_INTERNAL_ERROR = -6, /* a bug: please report it with the input */
  DYNRAD_OUTPUT_ERROR = -7    /* a file could not be written (missing directory, permission, disk full) */
} dynrad_status;

/* "0.1.0": the library's version. */
DYNRAD_API const char* dynrad_version(void);
/* DYNRAD_ABI_VERSION of the library; callers check it against their header's. */
DYNRAD_API int dynrad_abi_version(void);
/* "DYNRAD_OK", "DYNRAD_INVALID_INPUT", ...; "unknown status" otherwise. */
DYNRAD_API const char* dynrad_status_name(dynrad_status status);
/* The message of this thread's last failed call, or "" after a success. Never NULL. */
DYNRAD_API const char* dynrad_last_error(void);

/* ------------------------------------------------------------------------------ */
/* Scenes */

typedef struct dynrad_material {
  double reflectance[3]; /* linear rgb, each in [0, 1) */
  double emission[3];    /* W/m^2, each >= 0 */
  const char* name;      /* for messages; may be NULL ("material <index>") */
} dynrad_material;

typedef struct dynrad_scene dynrad_scene;

/* Builds a scene from a polygon soup and repairs it as the command line does (merges
 * close points, triangulates, snaps T-junctions, cuts non-manifold edges).
 * - positions: vertex_count * 3 doubles, x y z per vertex.
 * - polygon_sizes: corners of each of the polygon_count polygons (>= 3 each).
 * - polygon_indices: the polygons' vertex indices one after the other, as many as
 *   the sum of polygon_sizes, counter-clockwise seen from the front.
 * - polygon_materials: per polygon, an index into materials (material_count of them).
 * The arrays are copied; the caller may free them after the call.
 * DYNRAD_INVALID_INPUT names the first vertex, polygon or material at fault;
 * DYNRAD_NO_EMITTER when no polygon's material emits. */
DYNRAD_API dynrad_status dynrad_scene_create(const double* positions, size_t vertex_count,
                                             const uint32_t* polygon_indices, const uint32_t* polygon_sizes,
                                             size_t polygon_count, const uint32_t* polygon_materials,
                                             const dynrad_material* materials, size_t material_count,
                                             dynrad_scene** out_scene);
/* A scene from a file, as `dynrad solve` reads it (docs/scene-files.md): a model (OBJ,
 * PLY, OFF, STL, glTF, IFC, ...) or a JSON scene file with its luminaires, sky and sun,
 * calculation grids, cameras, observers, escape routes and light scenes. The file is
 * read, repaired and every section checked now (DYNRAD_INVALID_INPUT naming the file
 * and the line or entry; DYNRAD_NO_EMITTER comes from dynrad_solve, once the light
 * sources are known). Each dynrad_solve after the first reads the file again. */
DYNRAD_API dynrad_status dynrad_scene_load(const char* path, dynrad_scene** out_scene);
DYNRAD_API void dynrad_scene_destroy(dynrad_scene* scene);

/* ------------------------------------------------------------------------------ */
/* Options: the command line's `solve` options, with its defaults. */

typedef struct dynrad_options dynrad_options;

DYNRAD_API dynrad_status dynrad_options_create(dynrad_options** out_options);
DYNRAD_API void dynrad_options_destroy(dynrad_options* options);
/* "dynamic" (default), "progressive" or "adaptive". */
DYNRAD_API dynrad_status dynrad_options_set_method(dynrad_options* options, const char* method);
/* "draft", "normal" (default) or "high": as `dynrad solve --quality`, the estimated error
 * to stop at and the patches, levels and oracle that reach it, chosen from the model;
 * the setters below override. */
DYNRAD_API dynrad_status dynrad_options_set_quality(dynrad_options* options, const char* quality);
/* Paper levels (1 -> 4 splits) allowed below a patch, 0..12; default: the quality's
 * (dynamic), 3 (progressive, adaptive). */
DYNRAD_API dynrad_status dynrad_options_set_max_level(dynrad_options* options, int max_level);
/* Longest patch edge in model units; 0 (default): from the model's mean free path and the
 * quality (dynamic), a tenth of the bounding-box diagonal (progressive, adaptive). */
DYNRAD_API dynrad_status dynrad_options_set_patch_size(dynrad_options* options, double patch_size);
/* Stop when unshot power is below this fraction of emitted power, in [0, 1), instead of
 * by the quality's error target; default: the error target (dynamic), 0.01 (others). */
DYNRAD_API dynrad_status dynrad_options_set_converge(dynrad_options* options, double converge);
/* Stop after this many shots; 0 (default): no limit. */
DYNRAD_API dynrad_status dynrad_options_set_iterations(dynrad_options* options, uint64_t iterations);
/* Stop after this many seconds; 0 (default): no limit. */
DYNRAD_API dynrad_status dynrad_options_set_time_limit(dynrad_options* options, double seconds);
/* Worker threads, 0..1024; 0 (default): all cores. Results do not depend on it. */
DYNRAD_API dynrad_status dynrad_options_set_threads(dynrad_options* options, int threads);
/* Seed of all ray sampling; default 1. Same scene, options and seed: same result. */
DYNRAD_API dynrad_status dynrad_options_set_seed(dynrad_options* options, uint64_t seed);
/* Adaptive's gradient threshold (> 0), also all three of the paper oracle's; default 0.25. */
DYNRAD_API dynrad_status dynrad_options_set_threshold(dynrad_options* options, double threshold);
/* Dynamic's oracle: "pushdown" (default) or "paper" (Figure 6); see docs/algorithm.md. */
DYNRAD_API dynrad_status dynrad_options_set_oracle(dynrad_options* options, const char* oracle);
/* One of dynamic's thresholds (>= 0), by the command line's option name without
 * dashes: "cumulated_gradient" (of the oracle chosen so far), "current_gradient",
 * "current_ratio", "pushdown_error", "pushdown_floor", "pushdown_ambient" (0 off, else on). */
DYNRAD_API dynrad_status dynrad_options_set_oracle_threshold(dynrad_options* options, const char* name, double value);
/* Stop refining once the element tree holds this many elements; 0 (default): no limit. */
DYNRAD_API dynrad_status dynrad_options_set_max_elements(dynrad_options* options, uint64_t max_elements);
/* Add the ambient estimate of light not yet shot to the result's values (nonzero: on,
 * the default, as `dynrad solve`): an early stop (a cancel, a time limit) then shows close
 * to the converged picture. Output only; the solve is the same. */
DYNRAD_API dynrad_status dynrad_options_set_ambient(dynrad_options* options, int on);
/* Over-relax each shot by this factor, in (0, 2); 1 (default) is plain progressive
 * refinement, 1.3 needs fewer shots for a given accuracy. */
DYNRAD_API dynrad_status dynrad_options_set_overshoot(dynrad_options* options, double overshoot);
/* Per shot, receivers whose bounded share of its power is below this over the patch
 * count are skipped; in [0, 0.1], default 1e-4, 0 never. */
DYNRAD_API dynrad_status dynrad_options_set_negligible_share(dynrad_options* options, double share);
/* Merge the triangles of flat regions before patching (nonzero: on, the default, as
 * `dynrad solve`; 0: keep every triangle, as `--no-simplify`). Lossless for the light;
 * the result's mesh is a refinement of the merged one. */
DYNRAD_API dynrad_status dynrad_options_set_simplify(dynrad_options* options, int on);
/* Imprint where surfaces cross or touch, and remove the parts no light reaches
 * (nonzero: on, the default, as `dynrad solve`; 0: as `--no-imprint`). See docs/import-and-repair.md,
 * "Imprinting". */
DYNRAD_API dynrad_status dynrad_options_set_imprint(dynrad_options* options, int on);
/* Shape each shot's unshot radiosity by the sender's corners and a quarter grid of
 * points on it (nonzero: on, the default) or shoot it evenly (0: `--flat-senders`). */
DYNRAD_API dynrad_status dynrad_options_set_shaped_senders(dynrad_options* options, int on);
/* Display exposure (> 0) for dynrad_result_display; 0 (default): automatic, as the
 * command line (the 99th percentile of the lit surface's luminance, by area, maps to 0.9). */
DYNRAD_API dynrad_status dynrad_options_set_exposure(dynrad_options* options, double exposure);

/* ------------------------------------------------------------------------------ */
/* Solving */

typedef struct dynrad_result dynrad_result;

/* Called after every shot with the number of shots so far and the fraction of the
 * emitted power not yet shot. Return non-zero to stop at this shot boundary. */
typedef int (*dynrad_progress_fn)(uint64_t shot, double unshot_fraction, void* user);

/* Lights `scene` with `options` (NULL: defaults). `progress` (may be NULL) is called on
 * the calling thread. `cancel` (may be NULL) is read at every shot boundary; another
 * thread sets *cancel to non-zero to stop there. Either way of stopping returns
 * DYNRAD_STOPPED with a valid *out_result holding the solution so far; otherwise
 * DYNRAD_OK once a stop rule (converge, error target or floor, iterations, time limit)
 * holds (dynrad_report.stopped_by says which). On any other
 * status *out_result is set to NULL. The scene is not changed and may be solved again. */
DYNRAD_API dynrad_status dynrad_solve(const dynrad_scene* scene, const dynrad_options* options,
                                      dynrad_progress_fn progress, void* user, const volatile int* cancel,
                                      dynrad_result** out_result);
DYNRAD_API void dynrad_result_destroy(dynrad_result* result);

/* The refined mesh: vertices are split where surfaces meet at a crease or change
 * material, so each carries the value of one surface. 0 for a NULL result. */
DYNRAD_API size_t dynrad_result_vertex_count(const dynrad_result* result);
DYNRAD_API size_t dynrad_result_triangle_count(const dynrad_result* result);
/* x y z per vertex (3 doubles). */
DYNRAD_API dynrad_status dynrad_result_positions(const dynrad_result* result, double* xyz, size_t capacity);
/* Three vertex indices per triangle, counter-clockwise seen from the front. */
DYNRAD_API dynrad_status dynrad_result_triangles(const dynrad_result* result, uint32_t* indices, size_t capacity);
/* Per triangle: the index of its material in the scene's materials array. */
DYNRAD_API dynrad_status dynrad_result_triangle_materials(const dynrad_result* result, uint32_t* materials,
                                                          size_t capacity);
/* Per vertex: radiosity, linear rgb (3 floats), W/m^2. */
DYNRAD_API dynrad_status dynrad_result_radiosity(const dynrad_result* result, float* rgb, size_t capacity);
/* Per vertex: the light arriving on the front side (1 float): illuminance in lx in
 * photometric solves (a scene file with luminaires or a sky, as `dynrad solve` writes
 * its PLY's `illuminance`), otherwise irradiance in W/m^2 weighted as luminance
 * (0.2126 r + 0.7152 g + 0.0722 b). */
DYNRAD_API dynrad_status dynrad_result_illuminance(const dynrad_result* result, float* lux, size_t capacity);
/* Per vertex: display colour (3 bytes), sRGB-encoded radiosity x exposure, the same
 * bytes the command line writes as red/green/blue in its PLY. */
DYNRAD_API dynrad_status dynrad_result_display(const dynrad_result* result, uint8_t* rgb, size_t capacity);

typedef enum dynrad_stop_reason {
  DYNRAD_STOP_CONVERGED = 0,    /* the unshot fraction fell to dynrad_options.converge */
  DYNRAD_STOP_ITERATIONS = 1,   /* max_iterations shots */
  DYNRAD_STOP_TIME_LIMIT = 2,   /* time_limit seconds */
  DYNRAD_STOP_CANCELLED = 3,    /* progress callback or cancel flag */
  DYNRAD_STOP_ERROR_TARGET = 4, /* the estimated error fell to the error target */
  /* Stopped short of the error target: only the mesh's error was left above it, which
     shooting on would not lower (finer patches or a higher max level would). */
  DYNRAD_STOP_ERROR_FLOOR = 5
} dynrad_stop_reason;

typedef struct dynrad_report {
  uint64_t shots;                   /* progressive refinement iterations */
  uint64_t energy_transfers;        /* sender-to-element transfers, counted as the paper does */
  uint64_t patch_element_transfers; /* of those, to elements below patch level */
  uint64_t visibility_rays;
  uint64_t patches;
  uint64_t elements;
  double seconds;         /* solve time, without loading and repair */
  double unshot_fraction; /* of the emitted power, at the end */
  double exposure;        /* used by dynrad_result_display */
  double patch_size;      /* the one used, model units */
  double emitted[3];      /* power per channel (W when lengths are metres) */
  double absorbed[3];
  double escaped[3]; /* left through openings */
  int stopped_by;    /* a dynrad_stop_reason */
  double estimated_error; /* estimated mean relative error of the values (docs/report.md) */
} dynrad_report;

DYNRAD_API dynrad_status dynrad_result_report(const dynrad_result* result, dynrad_report* report);

/* The solve's report as JSON text (docs/report.md: its fields as `dynrad solve --report`
 * writes them), with "grids": per grid its name, points, Eavg, Emin, Emax and U0. Owned
 * by the result; "" for a NULL result. */
DYNRAD_API const char* dynrad_result_report_json(const dynrad_result* result);

/* The scene file's calculation grids (none for a scene made from arrays), in the file's
 * order: the grid's name (NULL for an index out of range), its point count, and per
 * point x, y, z and the illuminance (lx in photometric solves, W/m^2 otherwise; NaN
 * for a point inside a solid), 4 doubles per point, `capacity` in points. */
DYNRAD_API size_t dynrad_result_grid_count(const dynrad_result* result);
DYNRAD_API const char* dynrad_result_grid_name(const dynrad_result* result, size_t grid);
DYNRAD_API size_t dynrad_result_grid_point_count(const dynrad_result* result, size_t grid);
DYNRAD_API dynrad_status dynrad_result_grid_points(const dynrad_result* result, size_t grid, double* xyze,
                                                   size_t capacity);

/* Writes the lighting report as `dynrad solve --html` does: one HTML page at `path`
 * (the solve's facts, the light sources, each grid's figures and false-colour plan, the
 * views in true and false colour, the designer's checks), with the files it embeds
 * beside it, named after it as the command line names them after its output:
 * STEM_grids.json, STEM_grid_NAME.csv and .png, STEM_view_NAME.png and
 * STEM_view_NAME_luminance.png (STEM: path without its extension). Views and checks
 * need a scene file (dynrad_scene_load); a scene made from arrays gets the solve's
 * facts. Every path is checked before anything is written: DYNRAD_OUTPUT_ERROR naming
 * the file that cannot be, and nothing written. Existing files are replaced. */
DYNRAD_API dynrad_status dynrad_result_write_report(const dynrad_result* result, const char* path);

/* The report's false-colour scale (dark blue, blue, cyan, green, yellow, red) at t in
 * [0, 1] (clamped), as 3 sRGB bytes, so that a host's false colours match the report's
 * plans. DYNRAD_INVALID_ARGUMENT for a NULL rgb or a t that is not finite. */
DYNRAD_API dynrad_status dynrad_false_colour(double t, uint8_t rgb[3]);

#ifdef __cplusplus
}
#endif

#endif /* DYNRAD_DYNRAD_H */
