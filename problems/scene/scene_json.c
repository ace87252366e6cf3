/* scene_json.c - typed access to cJSON values with JSON-path errors. */
#include "scene/scene_json.h"

#include "io/num_format.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void rn_jwalk_init(rn_jwalk *w, rn_context *ctx, const char *file) {
  w->ctx = ctx;
  w->file = file;
  w->path[0] = '$';
  w->path[1] = '\0';
  w->len = 1;
}

static void jwalk_append(rn_jwalk *w, const char *s) {
  size_t n = strlen(s), cap = sizeof w->path;
  if (w->len + n + 1 > cap) n = cap - 1 - w->len;
  memcpy(w->path + w->len, s, n);
  w->len += n;
  w->path[w->len] = '\0';
}

static int is_identifier(const char *s) {
  if (!(isalpha((unsigned char)s[0]) || s[0] == '_')) return 0;
  for (; *s; s++)
    if (!(isalnum((unsigned char)*s) || *s == '_')) return 0;
  return 1;
}

size_t rn_jwalk_key(rn_jwalk *w, const char *key) {
  size_t mark = w->len;
  if (is_identifier(key)) {
    jwalk_append(w, ".");
    jwalk_append(w, key);
  } else {
    char buf[80];
    size_t j = 0;
    for (const char *p = key; *p && j + 1 < sizeof buf; p++)
      buf[j++] = (*p == '"' || *p == '\\' || (unsigned char)*p < 0x20) ? '?' : *p;
    buf[j] = '\0';
    jwalk_append(w, "[\"");
    jwalk_append(w, buf);
    jwalk_append(w, "\"]");
  }
  return mark;
}

size_t rn_jwalk_index(rn_jwalk *w, int i) {
  size_t mark = w->len; /* called for every element of big arrays: no printf */
  char buf[RN_NUM_BUF + 2];
  buf[0] = '[';
  size_t n = 1 + rn_format_long(i, buf + 1);
  buf[n++] = ']';
  buf[n] = '\0';
  jwalk_append(w, buf);
  return mark;
}

void rn_jwalk_pop(rn_jwalk *w, size_t mark) {
  if (mark <= w->len) {
    w->len = mark;
    w->path[mark] = '\0';
  }
}

#if defined(__GNUC__)
__attribute__((format(printf, 3, 0)))
#endif
static rn_status
jwalk_vfail(rn_jwalk *w, rn_status s, const char *fmt, va_list ap) {
  char reason[1024];
  vsnprintf(reason, sizeof reason, fmt, ap);
  for (char *p = reason; *p; p++) /* one line, always */
    if (*p == '\n' || *p == '\r') *p = ' ';
  return rn_context_set_error(w->ctx, s, "%s: %s: %s", w->file, w->path, reason);
}

rn_status rn_jwalk_fail(rn_jwalk *w, rn_status s, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  rn_status r = jwalk_vfail(w, s, fmt, ap);
  va_end(ap);
  return r;
}

rn_status rn_jwalk_error(rn_jwalk *w, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  rn_status r = jwalk_vfail(w, RN_ERR_PARSE, fmt, ap);
  va_end(ap);
  return r;
}

rn_status rn_jwalk_lib_error(rn_jwalk *w, rn_status s) {
  char msg[1024];
  const char *last = rn_context_last_error(w->ctx);
  snprintf(msg, sizeof msg, "%s", (last && *last) ? last : rn_status_message(s));
  return rn_jwalk_fail(w, s, "%s", msg);
}

void rn_json_describe(const cJSON *v, char *buf, size_t n) {
  if (!v)
    snprintf(buf, n, "nothing");
  else if (cJSON_IsNumber(v)) {
    if (isfinite(v->valuedouble))
      snprintf(buf, n, "%.17g", v->valuedouble);
    else
      snprintf(buf, n, "a number out of range (overflows to infinity)");
  } else if (cJSON_IsString(v)) {
    char s[48];
    size_t j = 0;
    for (const char *p = v->valuestring; p && *p && j + 1 < sizeof s; p++)
      s[j++] = ((unsigned char)*p < 0x20) ? '?' : *p;
    s[j] = '\0';
    snprintf(buf, n, "the string \"%s%s\"", s,
             (v->valuestring && strlen(v->valuestring) >= sizeof s - 1) ? "..." : "");
  } else if (cJSON_IsBool(v))
    snprintf(buf, n, "%s", cJSON_IsTrue(v) ? "true" : "false");
  else if (cJSON_IsNull(v))
    snprintf(buf, n, "null");
  else if (cJSON_IsArray(v))
    snprintf(buf, n, "an array of %d", cJSON_GetArraySize(v));
  else if (cJSON_IsObject(v))
    snprintf(buf, n, "an object");
  else
    snprintf(buf, n, "an invalid value");
}

static rn_status expected(rn_jwalk *w, const char *what, const cJSON *v) {
  char got[128];
  rn_json_describe(v, got, sizeof got);
  return rn_jwalk_error(w, "expected %s, got %s", what, got);
}

static int key_allowed(const char *key, const char *const *allowed) {
  for (; *allowed; allowed++)
    if (strcmp(key, *allowed) == 0) return 1;
  return 0;
}

static void join_keys(const char *const *allowed, char *buf, size_t n) {
  size_t len = 0;
  buf[0] = '\0';
  for (; *allowed && len + 1 < n; allowed++) {
    int k = snprintf(buf + len, n - len, "%s%s", len ? ", " : "", *allowed);
    if (k < 0) break;
    len += (size_t)k;
  }
}

rn_status rn_json_check_keys(rn_jwalk *w, const cJSON *obj, const char *const *allowed) {
  rn_status st = rn_jv_object(w, obj);
  if (st) return st;
  for (const cJSON *c = obj->child; c; c = c->next) {
    const char *key = c->string ? c->string : "";
    size_t mark = rn_jwalk_key(w, key);
    if (!key_allowed(key, allowed)) {
      char list[512];
      join_keys(allowed, list, sizeof list);
      st = rn_jwalk_error(w, "unknown key \"%s\" (allowed here: %s)", key, list);
    } else {
      for (const cJSON *d = obj->child; d != c; d = d->next)
        if (d->string && strcmp(d->string, key) == 0) {
          st = rn_jwalk_error(w, "duplicate key \"%s\"", key);
          break;
        }
    }
    rn_jwalk_pop(w, mark);
    if (st) return st;
  }
  return RN_OK;
}

rn_status rn_jv_object(rn_jwalk *w, const cJSON *v) {
  return cJSON_IsObject(v) ? RN_OK : expected(w, "an object", v);
}

rn_status rn_jv_array(rn_jwalk *w, const cJSON *v, int *count) {
  if (!cJSON_IsArray(v)) return expected(w, "an array", v);
  *count = cJSON_GetArraySize(v);
  return RN_OK;
}

rn_status rn_jv_number(rn_jwalk *w, const cJSON *v, rn_jrange r, double *out) {
  static const char *const what[] = {"a finite number", "a number > 0", "a number >= 0"};
  if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) return expected(w, what[r], v);
  double x = v->valuedouble;
  if ((r == RN_J_POSITIVE && !(x > 0)) || (r == RN_J_NONNEG && !(x >= 0)))
    return expected(w, what[r], v);
  *out = x;
  return RN_OK;
}

rn_status rn_jv_int(rn_jwalk *w, const cJSON *v, long lo, long hi, int *out) {
  if (cJSON_IsNumber(v) && isfinite(v->valuedouble)) {
    double x = v->valuedouble;
    if (x == floor(x) && x >= (double)lo && x <= (double)hi) {
      *out = (int)x;
      return RN_OK;
    }
  }
  char what[96];
  if (hi >= 2147483647L)
    snprintf(what, sizeof what, "an integer >= %ld", lo);
  else
    snprintf(what, sizeof what, "an integer in [%ld, %ld]", lo, hi);
  return expected(w, what, v);
}

rn_status rn_jv_string(rn_jwalk *w, const cJSON *v, const char **out) {
  if (!cJSON_IsString(v) || !v->valuestring) return expected(w, "a string", v);
  *out = v->valuestring;
  return RN_OK;
}

rn_status rn_jv_vec(rn_jwalk *w, const cJSON *v, int n, rn_jrange r, double *out) {
  if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n) {
    char what[64];
    snprintf(what, sizeof what, "an array of %d numbers", n);
    return expected(w, what, v);
  }
  int i = 0;
  for (const cJSON *c = v->child; c; c = c->next, i++) {
    size_t mark = rn_jwalk_index(w, i);
    rn_status st = rn_jv_number(w, c, r, &out[i]);
    rn_jwalk_pop(w, mark);
    if (st) return st;
  }
  return RN_OK;
}

const cJSON *rn_jm_get(const cJSON *obj, const char *key) {
  return cJSON_GetObjectItemCaseSensitive(obj, key);
}

rn_status rn_jm_require(rn_jwalk *w, const cJSON *obj, const char *key,
                        const cJSON **out) {
  *out = rn_jm_get(obj, key);
  if (!*out) return rn_jwalk_error(w, "missing required key \"%s\"", key);
  return RN_OK;
}

/* Locate obj[key]: *v NULL when absent and optional. */
static rn_status member(rn_jwalk *w, const cJSON *obj, const char *key, int required,
                        const cJSON **v, int *present) {
  *v = rn_jm_get(obj, key);
  if (present) *present = *v != NULL;
  if (!*v && required) return rn_jwalk_error(w, "missing required key \"%s\"", key);
  return RN_OK;
}

rn_status rn_jm_number(rn_jwalk *w, const cJSON *obj, const char *key, int required,
                       rn_jrange r, double *out, int *present) {
  const cJSON *v;
  rn_status st = member(w, obj, key, required, &v, present);
  if (st || !v) return st;
  size_t mark = rn_jwalk_key(w, key);
  st = rn_jv_number(w, v, r, out);
  rn_jwalk_pop(w, mark);
  return st;
}

rn_status rn_jm_int(rn_jwalk *w, const cJSON *obj, const char *key, int required, long lo,
                    long hi, int *out, int *present) {
  const cJSON *v;
  rn_status st = member(w, obj, key, required, &v, present);
  if (st || !v) return st;
  size_t mark = rn_jwalk_key(w, key);
  st = rn_jv_int(w, v, lo, hi, out);
  rn_jwalk_pop(w, mark);
  return st;
}

rn_status rn_jm_string(rn_jwalk *w, const cJSON *obj, const char *key, int required,
                       const char **out) {
  const cJSON *v;
  rn_status st = member(w, obj, key, required, &v, NULL);
  if (st || !v) return st;
  size_t mark = rn_jwalk_key(w, key);
  st = rn_jv_string(w, v, out);
  rn_jwalk_pop(w, mark);
  return st;
}

rn_status rn_jm_vec(rn_jwalk *w, const cJSON *obj, const char *key, int required, int n,
                    rn_jrange r, double *out, int *present) {
  const cJSON *v;
  rn_status st = member(w, obj, key, required, &v, present);
  if (st || !v) return st;
  size_t mark = rn_jwalk_key(w, key);
  st = rn_jv_vec(w, v, n, r, out);
  rn_jwalk_pop(w, mark);
  return st;
}
