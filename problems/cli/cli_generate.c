/* cli_generate.c - `rodnet generate KIND [options] -o SCENE.json`: lattice
 * scenes (lattice.h, lattice_scene.h; docs/lattices.md). */
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "generate/lattice.h"
#include "generate/lattice_check.h"
#include "generate/lattice_scene.h"
#include "generate/periodic_cell.h"

static const char generate_help[] =
    "Usage: rodnet generate KIND [options] -o SCENE.json\n"
    "\n"
    "Write a lattice of rods joined at joints as a JSON scene (explicit rods and\n"
    "joints) that 'rodnet solve' reads.  Every lattice node is a joint \"v<k>\",\n"
    "every bar a rod \"e<k>\"; geometry and numbering: docs/lattices.md.\n"
    "\n"
    "Kinds:\n"
    "  square, triangular, honeycomb, kagome   planar, in the xy plane\n"
    "  cubic, bcc, octet                       3D blocks\n"
    "  reentrant                               re-entrant (auxetic) honeycomb,\n"
    "                                          --periodic only\n"
    "\n"
    "Options:\n"
    "  -o, --output FILE        scene to write (required)\n"
    "      --cells NX[,NY[,NZ]] cells per direction (missing counts = NX; default 4)\n"
    "      --cell-size A        lattice period (default 1)\n"
    "      --edges-per-rod N    edges of each rod (default 8)\n"
    "      --section S          circle:R | rectangle:W,H | ellipse:A,B (W and A\n"
    "                           along d1 = +z for planar lattices; default\n"
    "                           circle with radius A/50)\n"
    "      --material E,NU      Young's modulus and Poisson's ratio (default 1,0.3)\n"
    "      --joint-model M      elastic (default) or rigid\n"
    "      --load L:VALUE       stretch-x|y|z:STRAIN  uniaxial, frictionless grips:\n"
    "                             pin the joints of the two faces normal to the\n"
    "                             axis along the axis only, displace the max face\n"
    "                             by STRAIN times the lattice's extent; a few more\n"
    "                             component pins remove the rigid motions (free\n"
    "                             lateral contraction)\n"
    "                           compress-x|y|z:STRAIN the same with -STRAIN\n"
    "                           (|STRAIN| < 1 for stretch, compress and grip)\n"
    "                           grip-x|y|z:STRAIN     gripped faces: the same with\n"
    "                             the face joints pinned in x, y and z (no lateral\n"
    "                             motion at the faces; STRAIN < 0 compresses)\n"
    "                           pull-x|y|z:FORCE      total FORCE on the max face,\n"
    "                             -FORCE on the min face whose centre joint is\n"
    "                             clamped (free lateral contraction)\n"
    "                           biaxial:EX,EY         (planar lattices) the x and\n"
    "                             y faces on frictionless grips, the max faces\n"
    "                             displaced by EX, EY times the extents\n"
    "                           shear:GAMMA           (planar lattices) the y\n"
    "                             faces gripped in x and y, the max one moved\n"
    "                             along x by GAMMA times the height\n"
    "                           With --periodic: biaxial and shear only, written\n"
    "                             as prescribed strains (E11, E22 or G12; the\n"
    "                             other components free)\n"
    "                           At most one --load.\n"
    "      --model M            planar or 3d: the scene's \"model\" (docs/model.md)\n";
static const char generate_help2[] =
    "      --periodic           write a periodic cell instead of a finite block:\n"
    "                           the --cells cells on the torus of their lattice\n"
    "                           vectors, rod ends at periodic images (\"image\"),\n"
    "                           no loads; for rodnet homogenize\n"
    "                           (docs/homogenization.md)\n"
    "      --slenderness T      (--periodic) strut thickness t = T times the mean\n"
    "                           bar length: square section t x t in 2D, circle of\n"
    "                           diameter t in 3D (default 0.05 without --section)\n"
    "      --relative-density R (--periodic) the same sections with t chosen so\n"
    "                           that the relative density is R\n"
    "      --perturb AMP        (--periodic) move every joint by a random vector\n"
    "                           with components in [-AMP, AMP] times the mean bar\n"
    "                           length (in plane for 2D cells): a disordered cell\n"
    "      --section-scatter S  (--periodic) scale every rod's section (radius, or\n"
    "                           width and height) by 1 + S g, g a standard normal\n"
    "                           deviate per rod (floored at 0.05): per-rod scatter\n"
    "      --seed N             seed of --perturb and --section-scatter (default 1)\n"
    "      --repeat M,N[,K]     (--periodic) write \"repeat\": the scene reader tiles\n"
    "                           the cell M x N (x K) times\n"
    "  -q, --quiet              no summary\n"
    "  -h, --help               show this help\n"
    "\n"
    "A section that does not make a lattice of rods (relative density 1 or\n"
    "more, struts that overlap along a whole bar at its joints) and numbers the\n"
    "scene reader cannot take back are refused (docs/lattices.md).  The scene's\n"
    "description is the command that writes the same file again.\n"
    "The file is written completely or not at all.\n"
    "Exit status: 0 written, 2 usage error, 3 the file cannot be written.\n";

typedef struct gen_args {
  const char *kind_name, *output, *section, *load;
  rn_lattice_kind kind;
  int cells[3], ncells, quiet, periodic, reentrant;
  double a, slenderness, density, perturb, scatter;
  int seed, repeat[3], nrepeat, has_seed;
  rn_lattice_scene sc;
  /* --section as given (sc.shape and sc.section may be replaced by the
   * --slenderness and --relative-density sections of a periodic cell) */
  rn_lattice_section_shape user_shape;
  double user_section[2];
} gen_args;

/* "x,y[,z]" into up to max numbers (doubles); count in *n; 0 if ok. */
static int parse_list(const char *s, int max, double *v, int *n) {
  *n = 0;
  const char *p = s;
  while (*n < max) {
    char *end = NULL;
    errno = 0;
    double x = strtod(p, &end);
    if (end == p || errno || !isfinite(x)) return -1;
    v[(*n)++] = x;
    if (*end == '\0') return 0;
    if (*end != ',') return -1;
    p = end + 1;
  }
  return -1;
}

static int parse_cells(gen_args *a, const char *v) {
  double c[3];
  int n = 0;
  if (parse_list(v, 3, c, &n) == 0) {
    int ok = 1;
    for (int k = 0; k < n; k++)
      ok &= c[k] == floor(c[k]) && c[k] >= 1 && c[k] <= RN_LATTICE_MAX_CELLS;
    if (ok) {
      for (int k = 0; k < 3; k++) a->cells[k] = (int)(k < n ? c[k] : c[0]);
      a->ncells = n;
      return 0;
    }
  }
  return rn_cli_usage_error("generate",
                            "--cells expects NX[,NY[,NZ]] with integers in [1, %d], "
                            "got '%s'",
                            RN_LATTICE_MAX_CELLS, v);
}

static int parse_section(gen_args *a, const char *v) {
  static const struct {
    const char *prefix;
    rn_lattice_section_shape shape;
    int n;
  } shapes[] = {{"circle:", RN_LSEC_CIRCLE, 1},
                {"rectangle:", RN_LSEC_RECTANGLE, 2},
                {"ellipse:", RN_LSEC_ELLIPSE, 2}};
  for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
    size_t len = strlen(shapes[i].prefix);
    if (strncmp(v, shapes[i].prefix, len) != 0) continue;
    double p[2];
    int n = 0;
    if (parse_list(v + len, 2, p, &n) == 0 && n == shapes[i].n && p[0] > 0 &&
        (n == 1 || p[1] > 0)) {
      a->sc.shape = shapes[i].shape;
      a->sc.section[0] = p[0];
      a->sc.section[1] = n == 2 ? p[1] : 0;
      a->user_shape = a->sc.shape;
      memcpy(a->user_section, a->sc.section, sizeof a->user_section);
      a->section = v;
      return 0;
    }
  }
  return rn_cli_usage_error("generate",
                            "--section expects circle:R, rectangle:W,H or ellipse:A,B "
                            "with lengths > 0, got '%s'",
                            v);
}

static int parse_material(gen_args *a, const char *v) {
  double p[2];
  int n = 0;
  if (parse_list(v, 2, p, &n) == 0 && n == 2 && p[0] > 0 && p[1] > -1 && p[1] <= 0.5) {
    a->sc.E = p[0];
    a->sc.nu = p[1];
    return 0;
  }
  return rn_cli_usage_error("generate",
                            "--material expects E,NU with E > 0 and -1 < NU <= 0.5, "
                            "got '%s'",
                            v);
}

/* biaxial:EX,EY and shear:GAMMA (docs/lattices.md); 1 if v is neither. */
static int parse_planar_load(gen_args *a, const char *v, int *rc) {
  double p[2];
  int n = 0, biaxial = strncmp(v, "biaxial:", 8) == 0;
  if (!biaxial && strncmp(v, "shear:", 6) != 0) return 1;
  *rc = 0;
  if (parse_list(v + (biaxial ? 8 : 6), biaxial ? 2 : 1, p, &n) != 0 ||
      n != (biaxial ? 2 : 1) || fabs(p[0]) >= 1 || (biaxial && fabs(p[1]) >= 1) ||
      (p[0] == 0 && (!biaxial || p[1] == 0)))
    *rc = rn_cli_usage_error("generate",
                             "--load expects biaxial:EX,EY or shear:GAMMA (strains of "
                             "magnitude below 1, not all 0), got '%s'",
                             v);
  a->sc.load = biaxial ? RN_LLOAD_BIAXIAL : RN_LLOAD_SHEAR;
  a->sc.load_value = p[0];
  a->sc.load_value2 = biaxial ? p[1] : 0.0;
  a->load = v;
  return 0;
}

static int parse_load(gen_args *a, const char *v) {
  static const char *const kinds[] = {"stretch-", "compress-", "pull-", "grip-"};
  int rc = 0;
  /* One load per scene: a second --load used to replace the first silently. */
  if (a->load)
    return rn_cli_usage_error("generate",
                              "--load given twice ('%s', then '%s'): a generated "
                              "scene takes one load",
                              a->load, v);
  if (parse_planar_load(a, v, &rc) == 0) return rc;
  static const rn_lattice_load_kind load[] = {RN_LLOAD_STRETCH, RN_LLOAD_STRETCH,
                                              RN_LLOAD_PULL, RN_LLOAD_GRIP};
  for (int k = 0; k < 4; k++) {
    size_t len = strlen(kinds[k]);
    if (strncmp(v, kinds[k], len) != 0) continue;
    const char *ax = v + len;
    char *end = NULL;
    double x = (ax[0] >= 'x' && ax[0] <= 'z' && ax[1] == ':') ? strtod(ax + 2, &end) : 0;
    if (end && end != ax + 2 && *end == '\0' && isfinite(x) && x != 0) {
      /* A strain of magnitude >= 1 moves the max face onto or past the min
       * face (compression) or is far outside the rods' small-strain range
       * (tension); compress-x:2 gave a mirror-inverted lattice. */
      if (load[k] != RN_LLOAD_PULL && fabs(x) >= 1)
        return rn_cli_usage_error("generate",
                                  "--load %s: the strain magnitude must be below 1, "
                                  "got %g",
                                  v, x);
      a->sc.load = load[k];
      a->sc.load_axis = ax[0] - 'x';
      a->sc.load_value = k == 1 ? -x : x;
      a->load = v;
      return 0;
    }
  }
  return rn_cli_usage_error("generate",
                            "--load expects stretch-AXIS:STRAIN, compress-AXIS:STRAIN, "
                            "grip-AXIS:STRAIN, pull-AXIS:FORCE (AXIS x, y or z; value "
                            "non-zero), biaxial:EX,EY or shear:GAMMA, got '%s'",
                            v);
}

static int parse_joint_model(gen_args *a, const char *v) {
  if (strcmp(v, "elastic") == 0)
    a->sc.joint_model = RN_JOINT_ELASTIC;
  else if (strcmp(v, "rigid") == 0)
    a->sc.joint_model = RN_JOINT_RIGID;
  else
    return rn_cli_usage_error("generate",
                              "--joint-model expects elastic or rigid, got '%s'", v);
  return 0;
}

/* opt's value v, a number in (0, hi) (range: how the message writes it). */
static int parse_below(const char *opt, const char *v, double hi, const char *range,
                       double *out) {
  int rc = rn_cli_parse_double("generate", opt, v, 0.0, out);
  if (!rc && !(*out < hi))
    rc = rn_cli_usage_error("generate", "%s expects a value in %s, got '%s'", opt, range,
                            v);
  return rc;
}

/* --repeat M,N[,K]. */
static int parse_repeat(gen_args *a, const char *v) {
  double r[3];
  int n = 0, ok = parse_list(v, 3, r, &n) == 0;
  for (int k = 0; ok && k < n; k++) ok = r[k] == floor(r[k]) && r[k] >= 1 && r[k] <= 1000;
  if (!ok)
    return rn_cli_usage_error(
        "generate", "--repeat expects M,N[,K] with integers in [1, 1000], got '%s'", v);
  for (int k = 0; k < 3; k++) a->repeat[k] = (int)(k < n ? r[k] : 1);
  a->nrepeat = n;
  return 0;
}

/* Value option number which (of parse_value_option's names) set to v; 0 or
 * an exit status. */
static int set_value_option(gen_args *a, int which, const char *v) {
  int rc = 0;
  switch (which) {
  case 0:
    a->output = v;
    break;
  case 1:
    rc = parse_cells(a, v);
    break;
  case 2:
    rc = rn_cli_parse_double("generate", "--cell-size", v, 0.0, &a->a);
    break;
  case 3:
    rc = rn_cli_parse_int("generate", "--edges-per-rod", v, 1, 100000L,
                          &a->sc.edges_per_rod);
    break;
  case 4:
    rc = parse_section(a, v);
    break;
  case 5:
    rc = parse_material(a, v);
    break;
  case 6:
    rc = parse_joint_model(a, v);
    break;
  case 13:
    if (strcmp(v, "planar") != 0 && strcmp(v, "3d") != 0)
      rc = rn_cli_usage_error("generate", "--model expects planar or 3d, got '%s'", v);
    a->sc.model = v;
    break;
  case 8:
    rc = rn_cli_parse_double("generate", "--slenderness", v, 0.0, &a->slenderness);
    break;
  case 9:
    rc = parse_below("--relative-density", v, 1.0, "(0, 1)", &a->density);
    break;
  case 10:
    rc = parse_below("--perturb", v, 0.5, "(0, 0.5)", &a->perturb);
    break;
  case 11:
    rc = rn_cli_parse_int("generate", "--seed", v, 0, 2147483647L, &a->seed);
    a->has_seed = 1;
    break;
  case 12:
    rc = parse_repeat(a, v);
    break;
  default:
    rc = parse_load(a, v);
    break;
  }
  return rc;
}

/* 1 if argv[*i] was a value option (*rc: 0 or an exit status). */
static int parse_value_option(int argc, char **argv, int *i, gen_args *a, int *rc) {
  static const char *const names[] = {"--output",           "--cells",   "--cell-size",
                                      "--edges-per-rod",    "--section", "--material",
                                      "--joint-model",      "--load",    "--slenderness",
                                      "--relative-density", "--perturb", "--seed",
                                      "--repeat",           "--model"};
  const char *v = NULL;
  int m = 0, which = -1;
  if ((m = rn_cli_option_value("generate", argc, argv, i, "--section-scatter", NULL,
                               &v))) {
    *rc = m < 0 ? RN_EXIT_USAGE
                : parse_below("--section-scatter", v, 1.0, "[0, 1)", &a->scatter);
    return 1;
  }
  for (int k = 0; k < 14 && m == 0; k++) {
    m = rn_cli_option_value("generate", argc, argv, i, names[k], k == 0 ? "-o" : NULL,
                            &v);
    which = k;
  }
  *rc = m < 0 ? RN_EXIT_USAGE : 0;
  if (m <= 0) return m != 0;
  *rc = set_value_option(a, which, v);
  return 1;
}

static void set_defaults(gen_args *a) {
  memset(a, 0, sizeof *a);
  a->cells[0] = a->cells[1] = a->cells[2] = 4;
  a->a = 1.0;
  a->sc.edges_per_rod = 8;
  a->sc.joint_model = RN_JOINT_ELASTIC;
  a->sc.E = 1.0;
  a->sc.nu = 0.3;
  a->sc.shape = RN_LSEC_CIRCLE;
  a->sc.load = RN_LLOAD_NONE;
  a->seed = 1;
}

/* The generator's kinds: those of lattice.h, then "reentrant" (a periodic cell
 * of its own, rn_pcell_reentrant).  The parser and the unknown-kind message
 * both walk this list, so the message cannot omit a kind. */
#define GEN_KIND_COUNT (RN_LATTICE_KIND_COUNT + 1)
static const char *gen_kind_name(int k) {
  return k < RN_LATTICE_KIND_COUNT ? rn_lattice_kind_name((rn_lattice_kind)k)
                                   : "reentrant";
}

/* a->kind and a->reentrant from a->kind_name; -1 if unknown. */
static int gen_kind_from_name(gen_args *a) {
  for (int k = 0; k < GEN_KIND_COUNT; k++)
    if (strcmp(a->kind_name, gen_kind_name(k)) == 0) {
      a->reentrant = k == RN_LATTICE_KIND_COUNT;
      /* planar; the re-entrant cell is built by rn_pcell_reentrant */
      a->kind = a->reentrant ? RN_LATTICE_HONEYCOMB : (rn_lattice_kind)k;
      return 0;
    }
  return -1;
}

static int unknown_kind(const char *name) {
  char list[256];
  size_t n = 0;
  list[0] = '\0';
  for (int k = 0; k < GEN_KIND_COUNT && n < sizeof list; k++)
    n += (size_t)snprintf(list + n, sizeof list - n, "%s%s", k ? ", " : "",
                          gen_kind_name(k));
  return rn_cli_usage_error("generate", "unknown lattice '%s' (known: %s)", name, list);
}

/* The options that need --periodic (or not), and the exclusive ones. */
static int check_periodic_options(const gen_args *a) {
  if (a->reentrant && !a->periodic)
    return rn_cli_usage_error("generate", "the reentrant lattice needs --periodic");
  if (!a->periodic && (a->slenderness > 0.0 || a->density > 0.0 || a->perturb > 0.0))
    return rn_cli_usage_error("generate",
                              "--slenderness, --relative-density and --perturb need "
                              "--periodic");
  if (!a->periodic && a->scatter > 0.0)
    return rn_cli_usage_error("generate", "--section-scatter needs --periodic");
  if (a->nrepeat && !a->periodic)
    return rn_cli_usage_error("generate", "--repeat needs --periodic");
  if (a->periodic && a->sc.load != RN_LLOAD_NONE && a->sc.load != RN_LLOAD_BIAXIAL &&
      a->sc.load != RN_LLOAD_SHEAR)
    return rn_cli_usage_error("generate",
                              "--load does not apply to a periodic cell except biaxial "
                              "and shear (prescribed strains), got '%s'",
                              a->load);
  if ((a->slenderness > 0.0) + (a->density > 0.0) + (a->section != NULL) > 1)
    return rn_cli_usage_error("generate", "give at most one of --section, --slenderness "
                                          "and --relative-density");
  return 0;
}

/* Lengths the scene reader can take back (docs/lattices.md): checked in full
 * on the lattice (check_struts); this first bound keeps the construction
 * itself finite. */
static int check_cell_size(const gen_args *a, int dim) {
  int cmax = a->cells[0] > a->cells[1] ? a->cells[0] : a->cells[1];
  if (dim == 3 && a->cells[2] > cmax) cmax = a->cells[2];
  if (!(a->a >= 4 * RN_GEN_MIN_LENGTH) || !(2.0 * a->a * cmax <= RN_GEN_MAX_LENGTH))
    return rn_cli_usage_error("generate",
                              "--cell-size %g: the cell size must be at least %g and "
                              "the lattice (cell size times %d cells, doubled) at most "
                              "%g",
                              a->a, 4 * RN_GEN_MIN_LENGTH, cmax, RN_GEN_MAX_LENGTH);
  return 0;
}

static int check_args(gen_args *a) {
  if (!a->kind_name) return rn_cli_usage_error("generate", "missing the lattice KIND");
  if (gen_kind_from_name(a) != 0) return unknown_kind(a->kind_name);
  int rc = check_periodic_options(a);
  if (rc) return rc;
  if (a->periodic && a->ncells == 0) /* one cell unless --cells asks for a supercell */
    a->cells[0] = a->cells[1] = a->cells[2] = 1;
  if (!a->output) return rn_cli_usage_error("generate", "missing -o SCENE.json");
  int dim = rn_lattice_kind_dimension(a->kind);
  if (a->nrepeat && a->nrepeat != dim)
    return rn_cli_usage_error("generate",
                              "--repeat: give one count per lattice vector (%d)", dim);
  if (a->ncells > dim)
    return rn_cli_usage_error("generate",
                              "--cells: the %s lattice is planar, give "
                              "NX[,NY]",
                              a->kind_name);
  if (dim == 3 && !a->periodic &&
      (a->sc.load == RN_LLOAD_BIAXIAL || a->sc.load == RN_LLOAD_SHEAR))
    return rn_cli_usage_error("generate",
                              "--load %s: biaxial and shear loads of a finite lattice "
                              "need a planar lattice (or --periodic)",
                              a->load);
  if (a->sc.model && strcmp(a->sc.model, "planar") == 0 && dim == 3)
    return rn_cli_usage_error("generate", "--model planar: the %s lattice is not planar",
                              a->kind_name);
  if (dim == 2 && a->sc.load != RN_LLOAD_NONE && a->sc.load_axis == 2)
    return rn_cli_usage_error("generate",
                              "--load: the %s lattice lies in the xy plane, load it "
                              "along x or y",
                              a->kind_name);
  /* the seed draws --perturb and --section-scatter only */
  if (a->has_seed && !(a->perturb > 0.0) && !(a->scatter > 0.0))
    return rn_cli_usage_error("generate", "--seed applies to --perturb and "
                                          "--section-scatter only");
  if ((rc = check_cell_size(a, dim))) return rc;
  if (!a->section) a->sc.section[0] = a->user_section[0] = a->a / 50;
  return 0;
}

/* 0 to go on, -1 help shown, otherwise an exit status. */
static int parse_generate_args(int argc, char **argv, gen_args *a) {
  set_defaults(a);
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    int rc = 0;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(generate_help, stdout);
      fputs(generate_help2, stdout);
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0)
      a->quiet = 1;
    else if (strcmp(s, "--periodic") == 0)
      a->periodic = 1;
    else if (parse_value_option(argc, argv, &i, a, &rc)) {
      if (rc) return rc;
    } else if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("generate", "unknown option '%s'", s);
    else if (a->kind_name)
      return rn_cli_usage_error("generate", "more than one KIND given ('%s' and '%s')",
                                a->kind_name, s);
    else
      a->kind_name = s;
  }
  static const char *const valued[] = {"--output|-o",       "--cells",
                                       "--cell-size",       "--edges-per-rod",
                                       "--section",         "--material",
                                       "--joint-model",     "--load",
                                       "--slenderness",     "--relative-density",
                                       "--perturb",         "--seed",
                                       "--repeat",          "--model",
                                       "--section-scatter", NULL};
  int rc = rn_cli_check_repeats("generate", argc, argv, valued);
  if (rc) return rc;
  if ((rc = check_args(a))) return rc;
  const rn_cli_file files[] = {{"-o", a->output, NULL, RN_CLI_OUT}};
  return rn_cli_check_files("generate", files, 1);
}

/* x with the fewest significant digits that read back as x (strtod). */
static const char *num(double x, char buf[32]) {
  for (int p = 1; p <= 17; p++) {
    snprintf(buf, 32, "%.*g", p, x);
    if (strtod(buf, NULL) == x) break;
  }
  return buf;
}

/* Appends printf(fmt, ...) to buf[n] at *len (truncation leaves *len >= n). */
static void append(char *buf, size_t n, size_t *len, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void append(char *buf, size_t n, size_t *len, const char *fmt, ...) {
  if (*len >= n) return;
  va_list ap;
  va_start(ap, fmt);
  int k = vsnprintf(buf + *len, n - *len, fmt, ap);
  va_end(ap);
  *len += k > 0 ? (size_t)k : 0;
}

/* " --load ..." from the parsed load (the canonical spelling, numbers that
 * read back exactly). */
static void describe_load(const gen_args *a, char *buf, size_t n, size_t *len) {
  char x[32], y[32];
  const char axis = (char)('x' + a->sc.load_axis);
  switch (a->sc.load) {
  case RN_LLOAD_STRETCH:
    append(buf, n, len, " --load stretch-%c:%s", axis, num(a->sc.load_value, x));
    break;
  case RN_LLOAD_GRIP:
    append(buf, n, len, " --load grip-%c:%s", axis, num(a->sc.load_value, x));
    break;
  case RN_LLOAD_PULL:
    append(buf, n, len, " --load pull-%c:%s", axis, num(a->sc.load_value, x));
    break;
  case RN_LLOAD_BIAXIAL:
    append(buf, n, len, " --load biaxial:%s,%s", num(a->sc.load_value, x),
           num(a->sc.load_value2, y));
    break;
  case RN_LLOAD_SHEAR:
    append(buf, n, len, " --load shear:%s", num(a->sc.load_value, x));
    break;
  default:
    break;
  }
}

/* The command that writes this very file (but -o) as the scene's description:
 * every option that shapes the file, in one canonical spelling, so that
 * running the description again writes the same bytes (docs/lattices.md).
 * The section is recorded the way it was given: --section, --slenderness or
 * --relative-density (the default of a periodic cell is --slenderness 0.05,
 * that of a finite block --section circle:A/50). */
static void describe(const gen_args *a, char *buf, size_t n) {
  int dim = rn_lattice_kind_dimension(a->kind);
  size_t len = 0;
  char x[32], y[32];
  append(buf, n, &len, "rodnet generate %s --cells %d,%d", a->kind_name, a->cells[0],
         a->cells[1]);
  if (dim == 3) append(buf, n, &len, ",%d", a->cells[2]);
  append(buf, n, &len, " --cell-size %s --edges-per-rod %d", num(a->a, x),
         a->sc.edges_per_rod);
  if (a->density > 0.0)
    append(buf, n, &len, " --relative-density %s", num(a->density, x));
  else if (a->slenderness > 0.0 || (a->periodic && !a->section))
    append(buf, n, &len, " --slenderness %s",
           num(a->slenderness > 0.0 ? a->slenderness : 0.05, x));
  else if (a->user_shape == RN_LSEC_CIRCLE)
    append(buf, n, &len, " --section circle:%s", num(a->user_section[0], x));
  else
    append(buf, n, &len, " --section %s:%s,%s",
           a->user_shape == RN_LSEC_RECTANGLE ? "rectangle" : "ellipse",
           num(a->user_section[0], x), num(a->user_section[1], y));
  append(buf, n, &len, " --material %s,%s --joint-model %s", num(a->sc.E, x),
         num(a->sc.nu, y), a->sc.joint_model == RN_JOINT_RIGID ? "rigid" : "elastic");
  describe_load(a, buf, n, &len);
  if (a->sc.model) append(buf, n, &len, " --model %s", a->sc.model);
  if (a->periodic) append(buf, n, &len, " --periodic");
  if (a->perturb > 0.0) append(buf, n, &len, " --perturb %s", num(a->perturb, x));
  if (a->scatter > 0.0) append(buf, n, &len, " --section-scatter %s", num(a->scatter, x));
  if (a->perturb > 0.0 || a->scatter > 0.0) append(buf, n, &len, " --seed %d", a->seed);
  if (a->nrepeat) {
    append(buf, n, &len, " --repeat %d,%d", a->repeat[0], a->repeat[1]);
    if (a->nrepeat == 3) append(buf, n, &len, ",%d", a->repeat[2]);
  }
}

static void print_summary(const gen_args *a, const rn_lattice *lat) {
  int nn = rn_lattice_num_nodes(lat), hist[64] = {0};
  for (int n = 0; n < nn; n++) {
    int v = rn_lattice_valence(lat, n);
    hist[v < 63 ? v : 63]++;
  }
  printf("rodnet generate: %s lattice, %d rods, %d joints (valence", a->kind_name,
         rn_lattice_num_bars(lat), nn);
  int first = 1;
  for (int v = 0; v < 64; v++)
    if (hist[v]) {
      printf("%s %d: %d", first ? "" : ",", v, hist[v]);
      first = 0;
    }
  printf("); wrote %s\n", a->output);
}

/* Square (2D) or round (3D) struts of thickness t from --slenderness or
 * --relative-density (or the default slenderness 0.05). */
static void pcell_section(gen_args *a, const rn_pcell *c) {
  double L, V, t;
  if (a->section) return;
  if (a->density > 0.0) {
    rn_pcell_section_for_density(c, a->density, &a->sc);
    return;
  }
  rn_pcell_measures(c, &L, &V);
  t = (a->slenderness > 0.0 ? a->slenderness : 0.05) * L / c->nbars;
  a->sc.shape = c->dim == 2 ? RN_LSEC_RECTANGLE : RN_LSEC_CIRCLE;
  a->sc.section[0] = c->dim == 2 ? t : 0.5 * t;
  a->sc.section[1] = t;
}

/* The option that set the section, for the messages of check_struts. */
static void section_source(const gen_args *a, char *buf, size_t n) {
  char x[32];
  if (a->density > 0.0)
    snprintf(buf, n, "--relative-density %s", num(a->density, x));
  else if (a->slenderness > 0.0)
    snprintf(buf, n, "--slenderness %s", num(a->slenderness, x));
  else if (a->section)
    snprintf(buf, n, "--section %s", a->section);
  else
    snprintf(buf, n, "the default section (%s)",
             a->periodic ? "--slenderness 0.05" : "circle of radius A/50");
}

/* The largest admissible value of the option that set the section, the
 * sections scaled by f (< 1) being the largest admissible, as text. */
static void admissible_bound(const gen_args *a, int dim, double f, char *bound,
                             size_t size) {
  const int p = dim == 2 ? 1 : 2;
  char x[32];
  if (a->density > 0.0)
    snprintf(bound, size, "--relative-density below %s", num(a->density * pow(f, p), x));
  else if (a->slenderness > 0.0)
    snprintf(bound, size, "--slenderness below %s", num(a->slenderness * f, x));
  else
    snprintf(bound, size, "section dimensions below %s times these", num(f, x));
}

/* A lattice of rods (docs/lattices.md, "Admissible sections"): the range of
 * what is written (readable back), then relative density below 1 and joint
 * zones that leave every bar a free length.  0 or an exit status (message
 * printed). */
static int check_struts(const gen_args *a, rn_context *ctx, int dim, int nn, int nb,
                        const int *uv, const double *d, const double *scale,
                        double measure, double extent) {
  double lmin = HUGE_VAL, lmax = 0.0, smin = 1.0, smax = 1.0;
  for (int e = 0; e < nb; e++) {
    const double *v = d + 3 * e, l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    lmin = fmin(lmin, l);
    lmax = isnan(l) ? l : fmax(lmax, l);
    if (scale) {
      smin = fmin(smin, scale[e]);
      smax = fmax(smax, scale[e]);
    }
  }
  if (!nb) lmin = lmax = 1.0;
  if (!isfinite(measure)) extent = HUGE_VAL;
  rn_status st = rn_generate_check_range(ctx, &a->sc, lmin, lmax, extent, smin, smax);
  if (st) {
    fprintf(stderr, "rodnet generate: %s: %s\n", a->output, rn_context_last_error(ctx));
    return RN_EXIT_USAGE;
  }
  rn_strut_bounds b;
  if (rn_strut_bounds_compute(dim, nn, nb, uv, d, scale, &a->sc, measure, &b)) {
    fprintf(stderr, "rodnet generate: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  char src[160];
  section_source(a, src, sizeof src);
  const char *kind = a->kind_name, *why = a->perturb > 0.0 ? " (--perturb)" : "";
  if (b.zero_bar >= 0)
    return rn_cli_usage_error("generate",
                              "%s: the %s cell has a bar of zero length (e%d)%s",
                              a->output, kind, b.zero_bar + 1, why);
  if (b.coincident_node >= 0)
    return rn_cli_usage_error("generate",
                              "%s: two bars of the %s cell leave joint v%d in one "
                              "direction%s",
                              a->output, kind, b.coincident_node + 1, why);
  if (b.factor > 1.0) return 0;
  char bound[96];
  admissible_bound(a, dim, b.factor, bound, sizeof bound);
  if (b.density >= 1.0)
    return rn_cli_usage_error(
        "generate",
        "%s: %s gives the %s lattice a relative density of %.6g (>= "
        "1): not a lattice of rods; use %s (docs/lattices.md)",
        a->output, src, kind, b.density, bound);
  return rn_cli_usage_error("generate",
                            "%s: with %s the struts of the %s lattice overlap at the "
                            "joints (the joint zones cover all of bar e%d)%s: not a "
                            "lattice of rods; use %s (docs/lattices.md)",
                            a->output, src, kind, b.joint_bar + 1, why, bound);
}

/* What the scene reader takes (problems/scene/scene_rods.c, scene_periodic.c): at
 * most 1e8 rod vertices; "repeat" at most 100000 copies and 2e6 rods and joints
 * once tiled.  0 or an exit status (message printed). */
#define GEN_MAX_VERTICES 100000000.0
static int check_readable(const gen_args *a, int nn, int nb) {
  double copies = 1.0;
  for (int k = 0; a->nrepeat && k < a->nrepeat; k++) copies *= a->repeat[k];
  const double vertices = copies * nb * (a->sc.edges_per_rod + 1.0);
  if (vertices > GEN_MAX_VERTICES)
    return rn_cli_usage_error("generate",
                              "%s: %d rods of %d edges%s make %.0f vertices: the scene "
                              "reader takes at most %.0f",
                              a->output, nb, a->sc.edges_per_rod,
                              a->nrepeat ? " (times --repeat)" : "", vertices,
                              GEN_MAX_VERTICES);
  if (a->nrepeat && (copies > 100000.0 || copies * (nn + nb) > 2000000.0))
    return rn_cli_usage_error("generate",
                              "%s: --repeat makes %.0f copies of %d rods and joints: the "
                              "scene reader tiles at most 100000 copies and 2000000 rods "
                              "and joints",
                              a->output, copies, nn + nb);
  return 0;
}

/* check_struts on a periodic cell (bar vectors to the image ends). */
static int check_pcell(const gen_args *a, rn_context *ctx, const rn_pcell *c) {
  int rc = check_readable(a, c->nnodes, c->nbars);
  if (rc) return rc;
  size_t nb1 = (size_t)(c->nbars ? c->nbars : 1);
  int *uv = malloc(2 * nb1 * sizeof(int));
  double *d = malloc(3 * nb1 * sizeof(double)), L, V, extent;
  if (!uv || !d) {
    free(uv);
    free(d);
    fprintf(stderr, "rodnet generate: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  extent = rn_pcell_bar_vectors(c, uv, d);
  rn_pcell_measures(c, &L, &V);
  rc = check_struts(a, ctx, c->dim, c->nnodes, c->nbars, uv, d, c->section_scale, V,
                    extent);
  free(uv);
  free(d);
  return rc;
}

/* check_struts on a finite block (the measure: its bounding box). */
static int check_lattice(const gen_args *a, rn_context *ctx, const rn_lattice *lat) {
  const int nn = rn_lattice_num_nodes(lat), nb = rn_lattice_num_bars(lat);
  int rc0 = check_readable(a, nn, nb);
  if (rc0) return rc0;
  const int dim = rn_lattice_kind_dimension(rn_lattice_get_kind(lat));
  int *uv = malloc(2 * (size_t)(nb ? nb : 1) * sizeof(int));
  double *d = malloc(3 * (size_t)(nb ? nb : 1) * sizeof(double)), V = 1.0, extent = 0.0;
  if (!uv || !d) {
    free(uv);
    free(d);
    fprintf(stderr, "rodnet generate: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  for (int e = 0; e < nb; e++) {
    double p[3], q[3];
    rn_lattice_bar(lat, e, uv + 2 * e);
    rn_lattice_node(lat, uv[2 * e], p);
    rn_lattice_node(lat, uv[2 * e + 1], q);
    for (int k = 0; k < 3; k++) d[3 * e + k] = q[k] - p[k];
  }
  for (int k = 0; k < dim; k++) {
    V *= rn_lattice_extent(lat, k);
    extent = fmax(extent, rn_lattice_extent(lat, k));
  }
  int rc = check_struts(a, ctx, dim, nn, nb, uv, d, NULL, V, extent);
  free(uv);
  free(d);
  return rc;
}

static int generate_periodic(gen_args *a, rn_context *ctx) {
  rn_pcell c;
  rn_status st = a->reentrant ? rn_pcell_reentrant(ctx, a->cells, a->a, &c)
                              : rn_pcell_from_lattice(ctx, a->kind, a->cells, a->a, &c);
  if (!st) {
    if (a->perturb > 0.0) rn_pcell_perturb(&c, a->perturb, (unsigned long)a->seed);
    pcell_section(a, &c);
    if (a->scatter > 0.0 &&
        rn_pcell_section_scatter(&c, a->scatter, (unsigned long)a->seed))
      st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
  }
  if (!st) {
    int rc = check_pcell(a, ctx, &c);
    if (rc) {
      rn_pcell_free(&c);
      return rc;
    }
    st = rn_pcell_write_scene(ctx, a->output, &c, &a->sc, a->nrepeat ? a->repeat : NULL);
  }
  if (st) {
    fprintf(stderr, "rodnet generate: %s\n", rn_context_last_error(ctx));
    rn_pcell_free(&c);
    return st == RN_ERR_IO                            ? RN_EXIT_INPUT
           : (st == RN_ERR_ARG || st == RN_ERR_RANGE) ? RN_EXIT_USAGE
                                                      : RN_EXIT_INTERNAL;
  }
  if (!a->quiet)
    printf("rodnet generate: periodic %s cell (%dD), %d rods, %d joints; wrote %s\n",
           a->kind_name, c.dim, c.nbars, c.nnodes, a->output);
  rn_pcell_free(&c);
  return RN_EXIT_OK;
}

int rn_cli_generate(int argc, char **argv) {
  gen_args a;
  int rc = parse_generate_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  char desc[1024];
  describe(&a, desc, sizeof desc);
  a.sc.description = desc;
  /* the output writable before the lattice is built (exit 3) */
  const rn_cli_file files[] = {{"-o", a.output, NULL, RN_CLI_OUT}};
  if ((rc = rn_cli_probe_outputs("generate", files, 1))) return rc;
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    fprintf(stderr, "rodnet generate: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  if (a.periodic) {
    rc = generate_periodic(&a, ctx);
    rn_context_destroy(&ctx);
    return rc;
  }
  rn_lattice *lat = NULL;
  rn_status st = rn_lattice_build(ctx, a.kind, a.cells, a.a, &lat);
  if (!st && (rc = check_lattice(&a, ctx, lat)) != 0) {
    rn_lattice_destroy(&lat);
    rn_context_destroy(&ctx);
    return rc;
  }
  if (!st) st = rn_lattice_write_scene(ctx, a.output, lat, &a.sc);
  if (st) {
    fprintf(stderr, "rodnet generate: %s\n", rn_context_last_error(ctx));
    rc = st == RN_ERR_IO                            ? RN_EXIT_INPUT
         : (st == RN_ERR_ARG || st == RN_ERR_RANGE) ? RN_EXIT_USAGE
                                                    : RN_EXIT_INTERNAL;
  } else if (!a.quiet)
    print_summary(&a, lat);
  rn_lattice_destroy(&lat);
  rn_context_destroy(&ctx);
  return rc;
}
