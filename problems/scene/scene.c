/* scene.c - JSON scene reader: file, top level, materials, sections, solver
 * block (rods in scene_rods.c, constraints and loads in scene_bcs.c). */
#include "scene/scene.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_contact.h"
#include "rodnet_model.h"
#include "rodnet_registry.h"
#include "scene/scene_internal.h"

static char *dup_string(const char *s) {
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d) memcpy(d, s, n);
  return d;
}

/* ---- file and JSON text ---------------------------------------------------- */

/* Read the whole file into a NUL-terminated buffer. */
static rn_status read_file(rn_context *ctx, const char *path, char **text, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f)
    return rn_context_set_error(ctx, RN_ERR_IO, "%s: cannot open: %s", path,
                                strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  rn_status st = buf ? RN_OK : RN_ERR_ALLOC;
  while (st == RN_OK) {
    if (n + 1 >= cap) {
      char *nb = realloc(buf, cap * 2);
      if (!nb) {
        st = RN_ERR_ALLOC;
        break;
      }
      buf = nb;
      cap *= 2;
    }
    size_t got = fread(buf + n, 1, cap - 1 - n, f);
    n += got;
    if (got == 0) {
      if (ferror(f)) st = RN_ERR_IO;
      break;
    }
  }
  int read_errno = errno;
  fclose(f);
  if (st) {
    free(buf);
    if (st == RN_ERR_ALLOC)
      return rn_context_set_error(ctx, st, "%s: out of memory reading the file", path);
    return rn_context_set_error(ctx, st, "%s: cannot read: %s", path,
                                strerror(read_errno));
  }
  buf[n] = '\0';
  *text = buf;
  *len = n;
  return RN_OK;
}

/* "FILE:LINE:COL: reason" for a position in text. */
static rn_status text_error(rn_context *ctx, const char *label, const char *text,
                            size_t len, size_t pos, const char *reason) {
  long line = 1, col = 1;
  if (pos > len) pos = len;
  for (size_t i = 0; i < pos; i++) {
    if (text[i] == '\n') {
      line++;
      col = 1;
    } else
      col++;
  }
  char near[32];
  size_t j = 0;
  for (size_t i = pos; i < len && j < 20 && text[i] != '\n'; i++)
    near[j++] = ((unsigned char)text[i] < 0x20 || text[i] == '\'') ? '?' : text[i];
  near[j] = '\0';
  if (j == 0)
    return rn_context_set_error(ctx, RN_ERR_PARSE, "%s:%ld:%ld: %s%s", label, line, col,
                                reason, pos >= len ? " (unexpected end of file)" : "");
  return rn_context_set_error(ctx, RN_ERR_PARSE, "%s:%ld:%ld: %s near '%s'", label, line,
                              col, reason, near);
}

/* text[len] need not be NUL-terminated: nothing past text[len - 1] is read
 * (cJSON gets a NUL-terminated copy, so that running off the end of the text
 * is reported as such). */
rn_status rn_json_parse_text(rn_context *ctx, const char *label, const char *text,
                             size_t len, cJSON **root) {
  const char *nul = memchr(text, '\0', len);
  if (nul)
    return text_error(ctx, label, text, len, (size_t)(nul - text),
                      "NUL byte in the file");
  size_t first = 0;
  while (first < len && strchr(" \t\r\n", text[first])) first++;
  if (first == len)
    return rn_context_set_error(ctx, RN_ERR_PARSE,
                                "%s: the file is empty (expected a "
                                "JSON object)",
                                label);
  char *copy = malloc(len + 1);
  if (!copy) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", label);
  memcpy(copy, text, len);
  copy[len] = '\0';
  const char *end = NULL;
  /* The length includes the terminating NUL: cJSON checks that nothing but
   * white space follows the value. */
  *root = cJSON_ParseWithLengthOpts(copy, len + 1, &end, 1);
  size_t pos = (end && end >= copy) ? (size_t)(end - copy) : 0;
  free(copy);
  if (*root) return RN_OK;
  return text_error(ctx, label, text, len, pos, "malformed JSON");
}

/* ---- materials and sections ------------------------------------------------ */

int rn_scene_parser_material(const rn_scene_parser *p, const char *name) {
  for (int i = 0; i < p->nmat; i++)
    if (strcmp(p->mat_names[i], name) == 0) return i;
  return -1;
}

int rn_scene_parser_section(const rn_scene_parser *p, const char *name) {
  for (int i = 0; i < p->nsec; i++)
    if (strcmp(p->sec_names[i], name) == 0) return i;
  return -1;
}

/* A non-empty object of named entries without duplicate names. */
static rn_status named_table(rn_jwalk *w, const cJSON *obj, const char *what,
                             int *count) {
  rn_status st = rn_jv_object(w, obj);
  if (st) return st;
  int n = 0;
  for (const cJSON *c = obj->child; c; c = c->next, n++) {
    for (const cJSON *d = obj->child; d != c; d = d->next)
      if (strcmp(d->string, c->string) == 0) {
        size_t mark = rn_jwalk_key(w, c->string);
        st = rn_jwalk_error(w, "duplicate %s name \"%s\"", what, c->string);
        rn_jwalk_pop(w, mark);
        return st;
      }
  }
  if (n == 0) return rn_jwalk_error(w, "expected at least one %s", what);
  *count = n;
  return RN_OK;
}

static rn_status read_material(rn_jwalk *w, const cJSON *v, rn_material *m) {
  static const char *const keys[] = {"E", "nu", "G", "density", NULL};
  double E = 0, nu = 0, G = 0, rho = 0;
  int has_nu = 0, has_G = 0;
  rn_status st = rn_json_check_keys(w, v, keys);
  if (!st) st = rn_jm_number(w, v, "E", 1, RN_J_POSITIVE, &E, NULL);
  if (!st) st = rn_jm_number(w, v, "nu", 0, RN_J_ANY, &nu, &has_nu);
  if (!st) st = rn_jm_number(w, v, "G", 0, RN_J_POSITIVE, &G, &has_G);
  if (!st) st = rn_jm_number(w, v, "density", 0, RN_J_NONNEG, &rho, NULL);
  if (st) return st;
  if (has_nu == has_G)
    return rn_jwalk_error(w, "give exactly one of \"nu\" (Poisson's ratio) and "
                             "\"G\" (shear modulus)");
  if (has_G) {
    m->E = E;
    m->G = G;
    m->density = rho;
    return RN_OK;
  }
  if (!(nu > -1.0 && nu <= 0.5)) {
    size_t mark = rn_jwalk_key(w, "nu");
    st = rn_jwalk_error(w, "expected a number in (-1, 0.5], got %.17g", nu);
    rn_jwalk_pop(w, mark);
    return st;
  }
  st = rn_material_from_E_nu(E, nu, rho, m);
  return st ? rn_jwalk_lib_error(w, st) : RN_OK;
}

static rn_status read_explicit_section(rn_jwalk *w, const cJSON *v, rn_section *s) {
  static const char *const keys[] = {"shape", "A", "I11", "I22", "I12", "J", NULL};
  rn_status st = rn_json_check_keys(w, v, keys);
  s->I12 = 0;
  if (!st) st = rn_jm_number(w, v, "A", 1, RN_J_POSITIVE, &s->A, NULL);
  if (!st) st = rn_jm_number(w, v, "I11", 1, RN_J_POSITIVE, &s->I11, NULL);
  if (!st) st = rn_jm_number(w, v, "I22", 1, RN_J_POSITIVE, &s->I22, NULL);
  if (!st) st = rn_jm_number(w, v, "I12", 0, RN_J_ANY, &s->I12, NULL);
  if (!st) st = rn_jm_number(w, v, "J", 1, RN_J_POSITIVE, &s->J, NULL);
  if (st) return st;
  if (!(s->I11 * s->I22 - s->I12 * s->I12 > 0)) {
    size_t mark = rn_jwalk_key(w, "I12");
    st = rn_jwalk_error(w,
                        "the bending stiffness is not positive definite: "
                        "need I11 * I22 - I12^2 > 0 (I12 = %.17g)",
                        s->I12);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

static rn_status read_shaped_section(rn_jwalk *w, const cJSON *v, const char *shape,
                                     rn_section *s) {
  static const char *const circle[] = {"shape", "radius", NULL};
  static const char *const hollow[] = {"shape", "outer_radius", "inner_radius", NULL};
  static const char *const ellipse[] = {"shape", "a", "b", NULL};
  static const char *const rect[] = {"shape", "width", "height", NULL};
  double a = 0, b = 0;
  rn_status st;
  if (strcmp(shape, "circle") == 0) {
    st = rn_json_check_keys(w, v, circle);
    if (!st) st = rn_jm_number(w, v, "radius", 1, RN_J_POSITIVE, &a, NULL);
    if (!st) st = rn_section_circle(a, s);
  } else if (strcmp(shape, "hollow_circle") == 0) {
    st = rn_json_check_keys(w, v, hollow);
    if (!st) st = rn_jm_number(w, v, "outer_radius", 1, RN_J_POSITIVE, &a, NULL);
    if (!st) st = rn_jm_number(w, v, "inner_radius", 1, RN_J_NONNEG, &b, NULL);
    if (!st && !(b < a)) {
      size_t mark = rn_jwalk_key(w, "inner_radius");
      st = rn_jwalk_error(w, "expected a number < outer_radius (%.17g), got %.17g", a, b);
      rn_jwalk_pop(w, mark);
      return st;
    }
    if (!st) st = rn_section_hollow_circle(a, b, s);
  } else if (strcmp(shape, "ellipse") == 0) {
    st = rn_json_check_keys(w, v, ellipse);
    if (!st) st = rn_jm_number(w, v, "a", 1, RN_J_POSITIVE, &a, NULL);
    if (!st) st = rn_jm_number(w, v, "b", 1, RN_J_POSITIVE, &b, NULL);
    if (!st) st = rn_section_ellipse(a, b, s);
  } else if (strcmp(shape, "rectangle") == 0) {
    st = rn_json_check_keys(w, v, rect);
    if (!st) st = rn_jm_number(w, v, "width", 1, RN_J_POSITIVE, &a, NULL);
    if (!st) st = rn_jm_number(w, v, "height", 1, RN_J_POSITIVE, &b, NULL);
    if (!st) st = rn_section_rectangle(a, b, s);
  } else {
    size_t mark = rn_jwalk_key(w, "shape");
    st = rn_jwalk_error(w,
                        "unknown shape \"%s\" (known: circle, hollow_circle, "
                        "ellipse, rectangle, explicit)",
                        shape);
    rn_jwalk_pop(w, mark);
    return st;
  }
  /* Parse errors carry their path already; a library error gets this one. */
  return (st && st != RN_ERR_PARSE) ? rn_jwalk_lib_error(w, st) : st;
}

static rn_status read_section(rn_jwalk *w, const cJSON *v, rn_section *s) {
  const char *shape = NULL;
  rn_status st = rn_jv_object(w, v);
  if (!st) st = rn_jm_string(w, v, "shape", 0, &shape);
  if (st) return st;
  if (!shape || strcmp(shape, "explicit") == 0)
    st = read_explicit_section(w, v, s);
  else
    st = read_shaped_section(w, v, shape, s);
  if (st) return st;
  st = rn_section_validate(s);
  return st ? rn_jwalk_lib_error(w, st) : RN_OK;
}

static rn_status read_materials(rn_scene_parser *p, const cJSON *obj) {
  rn_status st = named_table(&p->w, obj, "material", &p->nmat);
  if (st) return st;
  p->mat_names = calloc((size_t)p->nmat, sizeof *p->mat_names);
  p->mats = calloc((size_t)p->nmat, sizeof *p->mats);
  if (!p->mat_names || !p->mats)
    return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  int i = 0;
  for (const cJSON *c = obj->child; c && !st; c = c->next, i++) {
    size_t mark = rn_jwalk_key(&p->w, c->string);
    p->mat_names[i] = c->string;
    st = read_material(&p->w, c, &p->mats[i]);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}

static rn_status read_sections(rn_scene_parser *p, const cJSON *obj) {
  rn_status st = named_table(&p->w, obj, "section", &p->nsec);
  if (st) return st;
  p->sec_names = calloc((size_t)p->nsec, sizeof *p->sec_names);
  p->secs = calloc((size_t)p->nsec, sizeof *p->secs);
  if (!p->sec_names || !p->secs)
    return rn_jwalk_fail(&p->w, RN_ERR_ALLOC, "out of memory");
  int i = 0;
  for (const cJSON *c = obj->child; c && !st; c = c->next, i++) {
    size_t mark = rn_jwalk_key(&p->w, c->string);
    p->sec_names[i] = c->string;
    st = read_section(&p->w, c, &p->secs[i]);
    rn_jwalk_pop(&p->w, mark);
  }
  return st;
}

/* ---- solver block ---------------------------------------------------------- */

typedef struct solver_field {
  const char *key;
  rn_jrange range; /* for numbers */
  long lo;         /* for integers */
} solver_field;

/* Keys of the "solver" block in the order of solver_field_ptr. */
static const solver_field solver_fields[] = {
    {"max_iterations", RN_J_ANY, 1},  {"gtol", RN_J_POSITIVE, 0},
    {"gtol_abs", RN_J_NONNEG, 0},     {"step_tol", RN_J_NONNEG, 0},
    {"energy_tol", RN_J_NONNEG, 0},   {"krylov_max_iterations", RN_J_ANY, 1},
    {"krylov_tol", RN_J_POSITIVE, 0}, {"initial_radius", RN_J_NONNEG, 0},
    {"load_steps", RN_J_ANY, 0},      {"max_load_cuts", RN_J_ANY, 0},
    {"forcing", RN_J_NONNEG, 0},
};
enum { N_SOLVER_FIELDS = (int)(sizeof solver_fields / sizeof solver_fields[0]) };
#define SOLVER_BIT_METHOD (1u << N_SOLVER_FIELDS)
#define SOLVER_BIT_FACTORIZATION (1u << (N_SOLVER_FIELDS + 1))
#define SOLVER_BIT_PREDICTOR (1u << (N_SOLVER_FIELDS + 2))
#define SOLVER_BIT_PRECONDITIONER (1u << (N_SOLVER_FIELDS + 3))

/* The option field of solver_fields[i]: *ip for integers, *dp for numbers. */
static void solver_field_ptr(rn_solve_options *o, int i, int **ip, double **dp) {
  *ip = NULL;
  *dp = NULL;
  switch (i) {
  case 0:
    *ip = &o->max_iterations;
    break;
  case 1:
    *dp = &o->gtol_rel;
    break;
  case 2:
    *dp = &o->gtol_abs;
    break;
  case 3:
    *dp = &o->step_tol;
    break;
  case 4:
    *dp = &o->energy_tol;
    break;
  case 5:
    *ip = &o->krylov_max_iterations;
    break;
  case 6:
    *dp = &o->krylov_tol;
    break;
  case 7:
    *dp = &o->initial_radius;
    break;
  case 8:
    *ip = &o->load_steps;
    break;
  case 9:
    *ip = &o->max_load_cuts;
    break;
  default:
    *dp = &o->forcing;
    break;
  }
}

/* The names of a family, value i's (0, 1, ...; NULL past the last): solver kinds and
 * preconditioners from the library's registry (rodnet_registry.h, in every build:
 * a scene can be read by a build without the solver), factorisations as in
 * rn_factorization_name. */
typedef const char *(*name_at_fn)(size_t i);

static const char *solver_name_at(size_t i) {
  const rn_solver_info *row = rn_solver_info_at(i);
  return row ? row->name : NULL;
}

static const char *preconditioner_name_at(size_t i) {
  const rn_preconditioner_info *row = rn_preconditioner_info_at(i);
  return row ? row->name : NULL;
}

static const char *factorization_name_at(size_t i) {
  static const char *const names[] = {"auto", "banded", "sparse", "cholmod"};
  return i < sizeof names / sizeof names[0] ? names[i] : NULL;
}

/* The value of name in the family; -1 if absent. */
static int value_of_name(name_at_fn name_at, const char *name) {
  const char *n;
  for (size_t i = 0; (n = name_at(i)) != NULL; i++)
    if (strcmp(name, n) == 0) return (int)i;
  return -1;
}

/* Optional string key of the solver block naming a value of the family (what
 * receives -1 if the key is absent); an error naming the key otherwise. */
static rn_status read_solver_name(rn_scene_parser *p, const cJSON *v, const char *key,
                                  const char *what, name_at_fn name_at, int *value) {
  const char *name = NULL;
  *value = -1;
  rn_status st = rn_jm_string(&p->w, v, key, 0, &name);
  if (st || !name) return st;
  *value = value_of_name(name_at, name);
  if (*value >= 0) return RN_OK;
  char known[256] = "";
  const char *n;
  for (size_t i = 0; (n = name_at(i)) != NULL; i++) {
    size_t len = strlen(known);
    snprintf(known + len, sizeof known - len, "%s%s", i ? ", " : "", n);
  }
  size_t mark = rn_jwalk_key(&p->w, key);
  st = rn_jwalk_error(&p->w, "unknown %s \"%s\" (known: %s)", what, name, known);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

/* The solver block's string keys "method", "factorization" and "preconditioner". */
static rn_status read_solver_names(rn_scene_parser *p, const cJSON *v) {
  rn_scene *s = p->scene;
  int kind, fkind, pkind;
  rn_status st = read_solver_name(p, v, "method", "solver", solver_name_at, &kind);
  if (!st)
    st = read_solver_name(p, v, "factorization", "factorization", factorization_name_at,
                          &fkind);
  if (!st)
    st = read_solver_name(p, v, "preconditioner", "preconditioner",
                          preconditioner_name_at, &pkind);
  if (st) return st;
  if (pkind >= 0) {
    s->solver_opt.preconditioner = (rn_preconditioner)pkind;
    s->solver_set |= SOLVER_BIT_PRECONDITIONER;
  }
  if (kind >= 0) {
    s->solver_opt.solver = (rn_solver_kind)kind;
    s->solver_set |= SOLVER_BIT_METHOD;
  }
  if (fkind >= 0) {
    s->solver_opt.factorization = (rn_factorization)fkind;
    s->solver_set |= SOLVER_BIT_FACTORIZATION;
  }
  return RN_OK;
}

/* The solver block's boolean key "predictor" (optional). */
static rn_status read_solver_predictor(rn_scene_parser *p, const cJSON *v) {
  const cJSON *b = cJSON_GetObjectItemCaseSensitive(v, "predictor");
  if (!b) return RN_OK;
  if (!cJSON_IsBool(b)) {
    size_t mark = rn_jwalk_key(&p->w, "predictor");
    rn_status st = rn_jwalk_error(&p->w, "expected true or false");
    rn_jwalk_pop(&p->w, mark);
    return st;
  }
  p->scene->solver_opt.predictor = cJSON_IsTrue(b) ? 1 : 0;
  p->scene->solver_set |= SOLVER_BIT_PREDICTOR;
  return RN_OK;
}

static rn_status read_solver(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {
      "method",     "factorization",  "max_iterations", "gtol",
      "gtol_abs",   "step_tol",       "energy_tol",     "krylov_max_iterations",
      "krylov_tol", "initial_radius", "load_steps",     "max_load_cuts",
      "predictor",  "preconditioner", "forcing",        NULL};
  rn_scene *s = p->scene;
  rn_status st = rn_json_check_keys(&p->w, v, keys);
  if (!st) st = read_solver_names(p, v);
  if (!st) st = read_solver_predictor(p, v);
  for (int i = 0; i < N_SOLVER_FIELDS && !st; i++) {
    const solver_field *f = &solver_fields[i];
    int *ip, present = 0;
    double *dp;
    solver_field_ptr(&s->solver_opt, i, &ip, &dp);
    if (ip)
      st = rn_jm_int(&p->w, v, f->key, 0, f->lo, 2147483647L, ip, &present);
    else
      st = rn_jm_number(&p->w, v, f->key, 0, f->range, dp, &present);
    if (present) s->solver_set |= 1u << i;
  }
  return st;
}

int rn_scene_sets_solver_kind(const rn_scene *s) {
  return s && (s->solver_set & SOLVER_BIT_METHOD) ? 1 : 0;
}

void rn_scene_apply_solver(const rn_scene *s, rn_solve_options *opt) {
  rn_solve_options src = s->solver_opt;
  if (s->solver_set & SOLVER_BIT_METHOD) opt->solver = src.solver;
  if (s->solver_set & SOLVER_BIT_FACTORIZATION) opt->factorization = src.factorization;
  if (s->solver_set & SOLVER_BIT_PREDICTOR) opt->predictor = src.predictor;
  if (s->solver_set & SOLVER_BIT_PRECONDITIONER) opt->preconditioner = src.preconditioner;
  for (int i = 0; i < N_SOLVER_FIELDS; i++) {
    if (!(s->solver_set & (1u << i))) continue;
    int *ip_src, *ip_dst;
    double *dp_src, *dp_dst;
    solver_field_ptr(&src, i, &ip_src, &dp_src);
    solver_field_ptr(opt, i, &ip_dst, &dp_dst);
    if (ip_src)
      *ip_dst = *ip_src;
    else
      *dp_dst = *dp_src;
  }
}

/* ---- top level ------------------------------------------------------------- */

/* "radii": {"rod name": r, ...} of "contact": the rods whose contact radius
 * differs from "radius". */
static rn_status read_contact_radii(rn_scene_parser *p, const cJSON *v) {
  rn_jwalk *w = &p->w;
  rn_status st = rn_jv_object(w, v);
  const cJSON *item;
  cJSON_ArrayForEach(item, v) {
    if (st) break;
    size_t mark = rn_jwalk_key(w, item->string);
    double r = 0.0;
    int rod = rn_scene_find_rod(p->scene, item->string);
    if (rod < 0) st = rn_jwalk_error(w, "no rod named \"%s\"", item->string);
    if (!st) st = rn_jv_number(w, item, RN_J_NONNEG, &r);
    if (!st && (st = rn_network_set_rod_contact_radius(p->scene->net, rod, r)))
      st = rn_jwalk_lib_error(w, st);
    rn_jwalk_pop(w, mark);
  }
  return st;
}

/* "contact": {"distance": dhat, "stiffness": kappa, "radius": r, "radii": {...}}
 * (docs/contact.md). */
static rn_status read_contact(rn_scene_parser *p, const cJSON *v) {
  static const char *const keys[] = {"distance", "stiffness", "radius", "radii", NULL};
  double dhat = 0.0, kappa = 0.0, r = 0.0;
  rn_jwalk *w = &p->w;
  rn_status st = rn_jv_object(w, v);
  if (!st) st = rn_json_check_keys(w, v, keys);
  if (!st) st = rn_jm_number(w, v, "distance", 1, RN_J_POSITIVE, &dhat, NULL);
  if (!st) st = rn_jm_number(w, v, "stiffness", 1, RN_J_POSITIVE, &kappa, NULL);
  if (!st) st = rn_jm_number(w, v, "radius", 1, RN_J_NONNEG, &r, NULL);
  if (st) return st;
  if ((st = rn_network_set_contact(p->scene->net, dhat, kappa, r)))
    return rn_jwalk_lib_error(w, st);
  if (rn_jm_get(v, "radii")) {
    size_t mark = rn_jwalk_key(w, "radii");
    st = read_contact_radii(p, rn_jm_get(v, "radii"));
    rn_jwalk_pop(w, mark);
  }
  return st;
}

/* The value of top-level key steps[i] (read in this order). */
static rn_status read_step(rn_scene_parser *p, int i, const cJSON *v) {
  switch (i) {
  case 0:
    return read_materials(p, v);
  case 1:
    return read_sections(p, v);
  case 2:
    return rn_scene_read_graph(p, v);
  case 3:
    return rn_scene_read_rods(p, v);
  case 4:
    return rn_scene_read_joints(p, v);
  case 5:
    return rn_scene_read_constraints(p, v);
  case 6:
    return rn_scene_read_loads(p, v);
  default:
    return read_solver(p, v);
  }
}

/* The top-level "model" (optional): "planar" or "3d" (docs/model.md). */
static rn_status read_model(rn_scene_parser *p, const cJSON *root) {
  const char *name = NULL;
  rn_model model = RN_MODEL_AUTO;
  size_t mark;
  rn_status st = rn_jm_string(&p->w, root, "model", 0, &name);
  if (st || !name) return st;
  mark = rn_jwalk_key(&p->w, "model");
  if (!strcmp(name, "planar"))
    model = RN_MODEL_PLANAR;
  else if (!strcmp(name, "3d"))
    model = RN_MODEL_3D;
  else
    st = rn_jwalk_error(&p->w, "unknown model \"%s\" (known: planar, 3d)", name);
  if (!st && (st = rn_network_set_model(p->scene->net, model)))
    st = rn_scene_lib_error(p, st);
  rn_jwalk_pop(&p->w, mark);
  return st;
}

static rn_status read_scene_tree(rn_scene_parser *p, const cJSON *root) {
  static const char *const keys[] = {
      "description", "materials", "sections", "graph", "rods",    "joints", "constraints",
      "loads",       "solver",    "periodic", "model", "contact", NULL};
  static const char *const steps[] = {"materials", "sections",    "graph", "rods",
                                      "joints",    "constraints", "loads", "solver"};
  rn_jwalk *w = &p->w;
  const char *desc = NULL;
  rn_status st = rn_json_check_keys(w, root, keys);
  if (!st) st = rn_jm_string(w, root, "description", 0, &desc);
  if (st) return st;
  if (desc && !(p->scene->description = dup_string(desc)))
    return rn_jwalk_fail(w, RN_ERR_ALLOC, "out of memory");
  if ((st = read_model(p, root))) return st;
  /* Only a scene with a midpoint clamp needs its constraints while the rods are
   * read: the others would cost a scan of every constraint per rod (quadratic
   * on large lattices with many pins). */
  p->constraints = NULL;
  const cJSON *cons = rn_jm_get(root, "constraints");
  for (const cJSON *c = cons ? cons->child : NULL; c && !p->constraints; c = c->next)
    if (rn_jm_get(c, "at")) p->constraints = cons;
  if (rn_jm_get(root, "periodic")) { /* first: the cell precedes the rods */
    size_t mark = rn_jwalk_key(w, "periodic");
    st = rn_scene_read_periodic(p, rn_jm_get(root, "periodic"));
    rn_jwalk_pop(w, mark);
  }
  for (int i = 0; i < 8 && !st; i++) {
    const cJSON *v = rn_jm_get(root, steps[i]);
    if (!v) {
      if (i < 2)
        st = rn_jwalk_error(w, "missing required key \"%s\"", steps[i]);
      else if (i == 3 && !rn_jm_get(root, "graph"))
        st = rn_jwalk_error(w, "missing required key \"rods\" (or \"graph\", an OBJ "
                               "line graph)");
      continue;
    }
    size_t mark = rn_jwalk_key(w, steps[i]);
    st = read_step(p, i, v);
    rn_jwalk_pop(w, mark);
  }
  if (!st && rn_jm_get(root, "contact")) {
    size_t mark = rn_jwalk_key(w, "contact");
    st = read_contact(p, rn_jm_get(root, "contact"));
    rn_jwalk_pop(w, mark);
  }
  if (st) return st;
  st = rn_network_finalize(p->scene->net);
  return st ? rn_scene_finalize_error(p, st) : rn_scene_check_finite(p);
}

/* A scene, or the supercell its "periodic.repeat" asks for. */
static rn_status read_scene(rn_scene_parser *p, const cJSON *root) {
  cJSON *super = NULL;
  rn_status st = rn_scene_expand_repeat(p, root, &super);
  if (st || !super) return st ? st : read_scene_tree(p, root);
  st = read_scene_tree(p, super);
  cJSON_Delete(super);
  return st;
}

/* The network's mode (part NULL: whole). */
static rn_status set_mode(rn_network *net, const rn_scene_part *part) {
  if (!part || part->mode == RN_SCENE_WHOLE) return RN_OK;
  if (part->mode == RN_SCENE_GRAPH) return rn_network_set_graph_only(net);
  return rn_network_set_part(net, part->nparts, part->part, part->nrods, part->rod_nv,
                             part->rod_part, part->njoints, part->joint_ptr,
                             part->joint_rods);
}

static rn_status scene_new(rn_context *ctx, const char *label, const rn_scene_part *part,
                           rn_scene **out) {
  rn_scene *s = calloc(1, sizeof *s);
  if (!s) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", label);
  s->label = dup_string(label);
  rn_status st = s->label ? rn_network_create(ctx, &s->net) : RN_ERR_ALLOC;
  if (!st) st = set_mode(s->net, part);
  if (st) {
    rn_scene_destroy(&s);
    return rn_context_set_error(ctx, st, "%s: cannot create the network", label);
  }
  *out = s;
  return RN_OK;
}

static rn_status scene_parse(rn_context *ctx, const char *label, const char *text,
                             size_t len, const rn_scene_part *part, rn_scene **out) {
  if (!out) return RN_ERR_ARG;
  *out = NULL;
  if (!ctx || !text) return RN_ERR_ARG;
  if (!label) label = "<scene>";
  cJSON *root = NULL;
  rn_status st = rn_json_parse_text(ctx, label, text, len, &root);
  if (st) return st;
  rn_scene *s = NULL;
  st = scene_new(ctx, label, part, &s);
  if (!st) {
    rn_scene_parser p;
    memset(&p, 0, sizeof p);
    rn_jwalk_init(&p.w, ctx, label);
    p.scene = s;
    st = read_scene(&p, root);
    free(p.mat_names);
    free(p.mats);
    free(p.sec_names);
    free(p.secs);
  }
  cJSON_Delete(root);
  if (st)
    rn_scene_destroy(&s);
  else
    rn_context_clear_error(ctx);
  *out = s;
  return st;
}

rn_status rn_scene_parse(rn_context *ctx, const char *label, const char *text, size_t len,
                         rn_scene **out) {
  return scene_parse(ctx, label, text, len, NULL, out);
}

rn_status rn_scene_load_part(rn_context *ctx, const char *path, const rn_scene_part *part,
                             rn_scene **out) {
  if (!out) return RN_ERR_ARG;
  *out = NULL;
  if (!ctx || !path) return RN_ERR_ARG;
  char *text = NULL;
  size_t len = 0;
  rn_status st = read_file(ctx, path, &text, &len);
  if (st) return st;
  st = scene_parse(ctx, path, text, len, part, out);
  free(text);
  return st;
}

rn_status rn_scene_load(rn_context *ctx, const char *path, rn_scene **out) {
  return rn_scene_load_part(ctx, path, NULL, out);
}

void rn_scene_destroy(rn_scene **sp) {
  if (!sp || !*sp) return;
  rn_scene *s = *sp;
  for (int i = 0; i < s->nrods; i++) {
    free(s->rods[i].name);
    free(s->rods[i].pinned);
  }
  free(s->rods);
  for (int i = 0; i < s->njoints; i++) free(s->joints[i].name);
  free(s->joints);
  free(s->obj_path);
  rn_name_index_free(&s->rod_names);
  rn_name_index_free(&s->joint_names);
  rn_network_destroy(&s->net);
  free(s->label);
  free(s->description);
  free(s);
  *sp = NULL;
}

rn_network *rn_scene_network(const rn_scene *s) { return s ? s->net : NULL; }
const char *rn_scene_label(const rn_scene *s) { return s ? s->label : ""; }
const char *rn_scene_description(const rn_scene *s) {
  return (s && s->description) ? s->description : "";
}

int rn_scene_find_rod(const rn_scene *s, const char *name) {
  return s ? rn_name_index_get(&s->rod_names, name) : -1;
}

long rn_scene_num_vertices(const rn_scene *s) {
  long n = 0;
  for (int i = 0; s && i < s->nrods; i++) n += s->rods[i].nv;
  return n;
}
