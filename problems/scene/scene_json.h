/* scene_json.h - typed access to cJSON values with JSON-path error messages.
 *
 * Internal to problems/.  A walker keeps the file label and the JSON path of
 * the value being read ("$.rods[0].line"); every error is recorded in the
 * context as ONE line "FILE: $.path: reason" with status RN_ERR_PARSE.
 * Numbers must be finite (cJSON turns 1e999 into inf).  Lookups are
 * case-sensitive; rn_json_check_keys rejects unknown and duplicate keys.
 */
#ifndef RN_SCENE_JSON_H
#define RN_SCENE_JSON_H

#include <stddef.h>

#include <cjson/cJSON.h>

#include "rodnet.h"

typedef struct rn_jwalk {
  rn_context *ctx;
  const char *file; /* label in messages (borrowed) */
  char path[1024];  /* current JSON path, "$..." */
  size_t len;
} rn_jwalk;

/* Value constraints for numbers. */
typedef enum rn_jrange { RN_J_ANY = 0, RN_J_POSITIVE, RN_J_NONNEG } rn_jrange;

/* Parse text[len] (need not be NUL-terminated) as one JSON value into *root
 * (caller deletes); RN_ERR_PARSE "LABEL:LINE:COL: malformed JSON near '...'",
 * an empty file or a NUL byte likewise (scene.c). */
rn_status rn_json_parse_text(rn_context *ctx, const char *label, const char *text,
                             size_t len, cJSON **root);

void rn_jwalk_init(rn_jwalk *w, rn_context *ctx, const char *file);
/* Append ".key" (or ["key"]) / "[i]" to the path; return a mark for pop. */
size_t rn_jwalk_key(rn_jwalk *w, const char *key);
size_t rn_jwalk_index(rn_jwalk *w, int i);
void rn_jwalk_pop(rn_jwalk *w, size_t mark);
/* Record "FILE: PATH: reason" with status s; returns s. */
rn_status rn_jwalk_fail(rn_jwalk *w, rn_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Same with RN_ERR_PARSE. */
rn_status rn_jwalk_error(rn_jwalk *w, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Wrap the library's last error (status s) at the current path. */
rn_status rn_jwalk_lib_error(rn_jwalk *w, rn_status s);

/* Short description of a JSON value for "got ..." ("a string", "-1", ...). */
void rn_json_describe(const cJSON *v, char *buf, size_t n);

/* The value at the current path must be an object whose keys are all in
 * allowed (NULL-terminated), each at most once. */
rn_status rn_json_check_keys(rn_jwalk *w, const cJSON *obj, const char *const *allowed);

/* ---- values at the current path ------------------------------------------ */
rn_status rn_jv_object(rn_jwalk *w, const cJSON *v);
/* An array; *count receives its length. */
rn_status rn_jv_array(rn_jwalk *w, const cJSON *v, int *count);
rn_status rn_jv_number(rn_jwalk *w, const cJSON *v, rn_jrange r, double *out);
/* An integer in [lo, hi]. */
rn_status rn_jv_int(rn_jwalk *w, const cJSON *v, long lo, long hi, int *out);
rn_status rn_jv_string(rn_jwalk *w, const cJSON *v, const char **out);
/* An array of exactly n numbers. */
rn_status rn_jv_vec(rn_jwalk *w, const cJSON *v, int n, rn_jrange r, double *out);

/* ---- members of the object at the current path --------------------------- */
/* The member, or NULL if absent (error if required). */
const cJSON *rn_jm_get(const cJSON *obj, const char *key);
rn_status rn_jm_require(rn_jwalk *w, const cJSON *obj, const char *key,
                        const cJSON **out);
/* Typed members: *present (may be NULL) says whether the key was there;
 * a missing required key is an error, a missing optional one leaves *out. */
rn_status rn_jm_number(rn_jwalk *w, const cJSON *obj, const char *key, int required,
                       rn_jrange r, double *out, int *present);
rn_status rn_jm_int(rn_jwalk *w, const cJSON *obj, const char *key, int required, long lo,
                    long hi, int *out, int *present);
rn_status rn_jm_string(rn_jwalk *w, const cJSON *obj, const char *key, int required,
                       const char **out);
rn_status rn_jm_vec(rn_jwalk *w, const cJSON *obj, const char *key, int required, int n,
                    rn_jrange r, double *out, int *present);

#endif
