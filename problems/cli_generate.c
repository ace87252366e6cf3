/* cli_generate.c - `rodnet generate KIND [options] -o SCENE.json`: lattice
 * scenes (lattice.h, lattice_scene.h; docs/lattices.md). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lattice.h"
#include "lattice_scene.h"
#include "periodic_cell.h"

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
    "The file is written completely or not at all.\n"
    "Exit status: 0 written, 2 usage error, 3 the file cannot be written.\n";

typedef struct gen_args {
  const char *kind_name, *output, *section, *load;
  rn_lattice_kind kind;
  int cells[3], ncells, quiet, periodic, reentrant;
  double a, slenderness, density, perturb, scatter;
  int seed, repeat[3], nrepeat, has_seed;
  rn_lattice_scene sc;
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
    *rc = m < 0
              ? RN_EXIT_USAGE
              : rn_cli_parse_double("generate", "--section-scatter", v, 0.0, &a->scatter);
    if (!*rc && !(a->scatter < 1.0))
      *rc = rn_cli_usage_error(
          "generate", "--section-scatter expects a value in [0, 1), got '%s'", v);
    return 1;
  }
  for (int k = 0; k < 14 && m == 0; k++) {
    m = rn_cli_option_value("generate", argc, argv, i, names[k], k == 0 ? "-o" : NULL,
                            &v);
    which = k;
  }
  *rc = m < 0 ? RN_EXIT_USAGE : 0;
  if (m <= 0) return m != 0;
  switch (which) {
  case 0:
    a->output = v;
    break;
  case 1:
    *rc = parse_cells(a, v);
    break;
  case 2:
    *rc = rn_cli_parse_double("generate", "--cell-size", v, 0.0, &a->a);
    break;
  case 3:
    *rc = rn_cli_parse_int("generate", "--edges-per-rod", v, 1, 100000L,
                           &a->sc.edges_per_rod);
    break;
  case 4:
    *rc = parse_section(a, v);
    break;
  case 5:
    *rc = parse_material(a, v);
    break;
  case 6:
    *rc = parse_joint_model(a, v);
    break;
  case 13:
    if (strcmp(v, "planar") != 0 && strcmp(v, "3d") != 0)
      *rc = rn_cli_usage_error("generate", "--model expects planar or 3d, got '%s'", v);
    a->sc.model = v;
    break;
  case 8:
    *rc = rn_cli_parse_double("generate", "--slenderness", v, 0.0, &a->slenderness);
    break;
  case 9:
    *rc = rn_cli_parse_double("generate", "--relative-density", v, 0.0, &a->density);
    if (!*rc && !(a->density < 1.0))
      *rc = rn_cli_usage_error("generate",
                               "--relative-density expects a value in (0, 1), "
                               "got '%s'",
                               v);
    break;
  case 10:
    *rc = rn_cli_parse_double("generate", "--perturb", v, 0.0, &a->perturb);
    if (!*rc && !(a->perturb < 0.5))
      *rc = rn_cli_usage_error("generate",
                               "--perturb expects a value in (0, 0.5), got '%s'", v);
    break;
  case 11:
    *rc = rn_cli_parse_int("generate", "--seed", v, 0, 2147483647L, &a->seed);
    a->has_seed = 1;
    break;
  case 12: {
    double r[3];
    int n = 0, ok = parse_list(v, 3, r, &n) == 0;
    for (int k = 0; ok && k < n; k++)
      ok = r[k] == floor(r[k]) && r[k] >= 1 && r[k] <= 1000;
    if (!ok) {
      *rc = rn_cli_usage_error(
          "generate", "--repeat expects M,N[,K] with integers in [1, 1000], got '%s'", v);
      break;
    }
    for (int k = 0; k < 3; k++) a->repeat[k] = (int)(k < n ? r[k] : 1);
    a->nrepeat = n;
    break;
  }
  default:
    *rc = parse_load(a, v);
    break;
  }
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

static int check_args(gen_args *a) {
  if (!a->kind_name) return rn_cli_usage_error("generate", "missing the lattice KIND");
  a->reentrant = strcmp(a->kind_name, "reentrant") == 0;
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
  if (a->periodic && a->ncells == 0) /* one cell unless --cells asks for a supercell */
    a->cells[0] = a->cells[1] = a->cells[2] = 1;
  if (a->reentrant) {
    a->kind = RN_LATTICE_HONEYCOMB; /* planar; the cell is built by rn_pcell_reentrant */
  } else if (rn_lattice_kind_from_name(a->kind_name, &a->kind) != 0)
    return rn_cli_usage_error("generate",
                              "unknown lattice '%s' (known: square, triangular, "
                              "honeycomb, kagome, cubic, bcc, octet)",
                              a->kind_name);
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
  if (!a->section) a->sc.section[0] = a->a / 50;
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

/* "rodnet generate ..." as the scene's description. */
static void describe(const gen_args *a, char *buf, size_t n) {
  int dim = rn_lattice_kind_dimension(a->kind);
  int len = snprintf(buf, n, "rodnet generate %s --cells %d,%d", a->kind_name,
                     a->cells[0], a->cells[1]);
  if (dim == 3 && len > 0 && (size_t)len < n)
    len += snprintf(buf + len, n - (size_t)len, ",%d", a->cells[2]);
  char section[64];
  if (a->section)
    snprintf(section, sizeof section, "%s", a->section);
  else
    snprintf(section, sizeof section, "circle:%.15g", a->sc.section[0]);
  if (len > 0 && (size_t)len < n)
    len += snprintf(buf + len, n - (size_t)len,
                    " --cell-size %.15g --edges-per-rod %d --section %s --material "
                    "%.15g,%.15g --joint-model %s",
                    a->a, a->sc.edges_per_rod, section, a->sc.E, a->sc.nu,
                    a->sc.joint_model == RN_JOINT_RIGID ? "rigid" : "elastic");
  if (a->load && len > 0 && (size_t)len < n)
    len += snprintf(buf + len, n - (size_t)len, " --load %s", a->load);
  if (a->sc.model && len > 0 && (size_t)len < n)
    len += snprintf(buf + len, n - (size_t)len, " --model %s", a->sc.model);
  if (a->periodic && len > 0 && (size_t)len < n)
    snprintf(buf + len, n - (size_t)len, " --periodic");
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
