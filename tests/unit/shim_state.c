/* shim_state.c - state snapshots (rn_network_state_save / _restore) on a
 * portal frame with a rigid and an elastic corner joint, a clamped joint with
 * a prescribed rotation, couples on a rod and on a joint (shim_networks.h):
 *  - solved at load factor 0.5, saved; every evaluation there (energy, energy
 *    terms, gradient, HVP, Hessian values, joint rotations, rod frames and
 *    strains) is recorded;
 *  - solved away (load factor 1, then extra reference updates at perturbed
 *    states), restored: the load factor, the DOFs and every evaluation are
 *    bit-identical to the recorded ones; twice (the snapshot stays valid);
 *  - the former continuation restore (set the DOFs back and transport the
 *    reference to them) is printed for comparison: it does not give back the
 *    rigid joint's rotation;
 *  - error paths: NULL arguments, before finalize, a snapshot of another
 *    network; destroy accepts NULL. */
#include "shim_networks.h"

typedef struct record {
  double lambda, E, terms[RN_TERM_COUNT];
  double *x, *g, *hv, *hvals, *phys, *strain;
  size_t n, nnz, nphys, nstrain;
} record;

static double *strains(const rn_network *net, size_t *len) {
  size_t n = 0, at = 0;
  double *v;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    n += (size_t)(nv - 1) + 3 * (size_t)(nv - 2);
  }
  v = calloc(n, sizeof(double));
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    double *s = v + at, *k = s + (nv - 1), *t = k + 2 * (nv - 2);
    CHECK_STATUS(rn_network_rod_strains(net, r, s, k, t), RN_OK);
    at += (size_t)(nv - 1) + 3 * (size_t)(nv - 2);
  }
  *len = n;
  return v;
}

static void take(const rn_network *net, const double *v, record *r) {
  const int64_t *rowptr;
  const int32_t *col;
  r->n = rn_network_num_dofs(net);
  CHECK_STATUS(rn_network_hessian_pattern(net, &r->nnz, &rowptr, &col), RN_OK);
  r->lambda = rn_network_load_factor(net);
  r->x = calloc(r->n, sizeof(double));
  r->g = calloc(r->n, sizeof(double));
  r->hv = calloc(r->n, sizeof(double));
  r->hvals = calloc(r->nnz, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, r->x), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, r->x, &r->E, r->g), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, r->x, r->terms), RN_OK);
  CHECK_STATUS(rn_network_hvp(net, r->x, v, r->hv), RN_OK);
  CHECK_STATUS(rn_network_hessian_values(net, r->x, r->hvals), RN_OK);
  r->phys = shimnet_physical_state(net, &r->nphys);
  r->strain = strains(net, &r->nstrain);
}

static void drop(record *r) {
  free(r->x);
  free(r->g);
  free(r->hv);
  free(r->hvals);
  free(r->phys);
  free(r->strain);
}

static int same(const double *a, const double *b, size_t n) {
  return memcmp(a, b, n * sizeof(double)) == 0;
}

static void check_identical(const record *a, const record *b) {
  CHECK(a->lambda == b->lambda);
  CHECK(memcmp(&a->E, &b->E, sizeof(double)) == 0);
  CHECK(same(a->terms, b->terms, RN_TERM_COUNT));
  CHECK(same(a->x, b->x, a->n));
  CHECK(same(a->g, b->g, a->n));
  CHECK(same(a->hv, b->hv, a->n));
  CHECK(same(a->hvals, b->hvals, a->nnz));
  CHECK(a->nphys == b->nphys && same(a->phys, b->phys, a->nphys));
  CHECK(a->nstrain == b->nstrain && same(a->strain, b->strain, a->nstrain));
}

/* Moves the network away from the saved state: full load, then two reference
 * updates at perturbed states. */
static void solve_away(rn_network *net, const record *saved) {
  rn_solve_report rep;
  double *x = calloc(saved->n, sizeof(double));
  uint64_t seed = 11;
  CHECK_STATUS(rn_network_set_load_factor(net, 1.0), RN_OK);
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  for (int k = 0; k < 2; ++k) {
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    for (size_t i = 0; i < saved->n; ++i) x[i] += 1e-3 * rn_test_rand(&seed);
    CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
    CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  }
  free(x);
}

/* The continuation restore the shim used before snapshots: DOFs set back at the
 * saved load factor and the reference transported to them.  Returns the largest
 * difference of the joint rotations to the saved ones. */
static double transport_restore_error(rn_network *net, const record *saved) {
  double *x = calloc(saved->n, sizeof(double)), err = 0.0;
  size_t np;
  double *phys;
  memcpy(x, saved->x, saved->n * sizeof(double));
  CHECK_STATUS(rn_network_set_load_factor(net, saved->lambda), RN_OK);
  CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  phys = shimnet_physical_state(net, &np);
  for (int j = 0; j < rn_network_num_joints(net); ++j)
    for (int c = 0; c < 9; ++c) {
      const size_t at =
          np - 12 * (size_t)(rn_network_num_joints(net) - j) + 3 + (size_t)c;
      err = fmax(err, fabs(phys[at] - saved->phys[at]));
    }
  free(phys);
  free(x);
  return err;
}

static void check_errors(rn_context *ctx, rn_network *net, const rn_state *s) {
  rn_network *other = shimnet_portal(ctx, RN_JOINT_RIGID, RN_JOINT_ELASTIC, 8, 0.1, 0);
  static int marker;
  rn_state *t = (rn_state *)(void *)&marker;
  CHECK_STATUS(rn_network_state_save(other, &t), RN_ERR_STATE);
  CHECK(t == NULL);
  CHECK_STATUS(rn_network_state_restore(other, s), RN_ERR_STATE);
  CHECK_STATUS(rn_network_finalize(other), RN_OK);
  CHECK_STATUS(rn_network_state_restore(other, s), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "another network") != NULL);
  CHECK_STATUS(rn_network_state_save(NULL, &t), RN_ERR_ARG);
  CHECK_STATUS(rn_network_state_save(net, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_state_restore(NULL, s), RN_ERR_ARG);
  CHECK_STATUS(rn_network_state_restore(net, NULL), RN_ERR_ARG);
  rn_state_destroy(NULL);
  t = NULL;
  rn_state_destroy(&t);
  CHECK(t == NULL);
  rn_network_destroy(&other);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_network *net;
  rn_state *snap = NULL;
  rn_solve_report rep;
  record saved, now;
  double *v, err;
  uint64_t seed = 3;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  net = shimnet_portal(ctx, RN_JOINT_RIGID, RN_JOINT_ELASTIC, 8, 0.1, 1);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  CHECK_STATUS(rn_network_state_save(net, &snap), RN_OK);
  CHECK(snap != NULL);
  v = calloc(rn_network_num_dofs(net), sizeof(double));
  for (size_t i = 0; i < rn_network_num_dofs(net); ++i) v[i] = rn_test_rand(&seed);
  take(net, v, &saved);

  for (int round = 0; round < 2; ++round) {
    solve_away(net, &saved);
    take(net, v, &now);
    CHECK(!same(now.g, saved.g, saved.n)); /* it did move */
    drop(&now);
    CHECK_STATUS(rn_network_state_restore(net, snap), RN_OK);
    take(net, v, &now);
    check_identical(&now, &saved);
    drop(&now);
  }

  solve_away(net, &saved);
  err = transport_restore_error(net, &saved);
  printf("joint rotations after the former transport restore: max difference %.3e "
         "(snapshot restore: 0)\n",
         err);

  check_errors(ctx, net, snap);
  rn_state_destroy(&snap);
  CHECK(snap == NULL);
  drop(&saved);
  free(v);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_state");
}
