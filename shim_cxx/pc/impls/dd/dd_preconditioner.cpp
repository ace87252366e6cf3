// dd_preconditioner.cpp - rod-level domain decomposition (see dd_preconditioner.hpp):
// its structure (build), numeric set-up (numeric) and application (apply).  The rod
// blocks are in rod_blocks.cpp, the direct coarse solve in direct_coarse.cpp, the
// coarse nodes and near-null space of the AMG coarse solve in amg_coarse.cpp.
#include "pc/impls/dd/dd_preconditioner.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "pc/impls/dd/amg_coarse.hpp"
#include "pc/impls/dd/dd_common.hpp"
#include "pc/impls/dd/rod_blocks.hpp"
#include "pc/spd_guard.hpp"
#include "system/dof_blocks.hpp"

namespace rodnet {

using namespace dd;

// ---- the domain decomposition -------------------------------------------------------
struct DdPreconditioner::Impl {
  // structure, built at the first setup (and again if the Hessian's graph changes)
  Teuchos::RCP<const TCrs::crs_graph_type> hgraph;
  Teuchos::RCP<const TMap> map, cmap, cov; // system map, owned / overlapping coarse
  std::vector<LO> iface_rows;              // owned local row of owned coarse row k
  std::vector<Rod> rods;
  std::vector<size_t> gg_src, gg_dst; // H_GG: H value index -> Sov value index
  std::vector<size_t> gg_diag;        // the gg entries on H's diagonal
  std::vector<size_t> cross;  // H entries between two rods' interiors: must be zero
  std::vector<size_t> sdiag;  // S value index of each owned coarse row's diagonal
  std::vector<size_t> s_copy; // S value index of each Sov value (no ghosts: no export)
  Teuchos::RCP<TCrs> Sov, S;
  Teuchos::RCP<const Tpetra::Export<>> exporter; // cov -> cmap
  Teuchos::RCP<const Tpetra::Import<>> importer; // cmap -> cov
  Teuchos::RCP<TMV> nullspace;
  std::unique_ptr<CoarseSolver> coarse;
  long long coarse_rows = 0, rods_shifted = 0;
  double declined_flops = 0.0; // of the direct coarse solve the automatic choice declined
  bool S_built = false;
  // work (apply)
  mutable Teuchos::RCP<TMV> bov, b, y, yov;
  mutable std::vector<double> t, w;

  void build(const System &sys, const TCrs &H);
  // build()'s steps.  The coarse numbering: nodes of 6 rows (coarse_nodes), those of
  // rank p after those of ranks < p; dummy rows (iface_rows -1) pad every node to 6.
  struct Numbering {
    std::vector<int> slot;           // coarse slot of every interface DOF
    std::vector<double> node_points; // 3 per node
    long long nif = 0;               // owned coarse rows (6 per node)
    GO offset = 0;                   // GID of the first
    std::vector<GO> ccol;    // coarse GID of every column of H (-1: a rod interior)
    std::vector<LO> col2row; // owned row of every column of H (invalid: not owned)
  };
  Numbering number_coarse(const DofBlocks &blk, const TCrs &H);
  std::vector<GO> build_rods(const DofBlocks &blk, const TCrs &H, const Numbering &cn,
                             std::vector<std::vector<GO>> &rod_gids);
  void scan_rod(size_t ir, const DofBlocks &blk, const TCrs::local_matrix_host_type &lcl,
                const Numbering &cn, const std::vector<int> &pos,
                std::vector<GO> &coupled);
  void coarse_graph(const TCrs &H, const Numbering &cn, const std::vector<GO> &ovg,
                    const std::vector<std::vector<GO>> &rod_gids,
                    std::vector<std::pair<size_t, GO>> &gg, std::vector<size_t> &gg_row);
  void locate_coarse_entries(const std::vector<std::vector<GO>> &rod_gids,
                             const std::vector<std::pair<size_t, GO>> &gg,
                             const std::vector<size_t> &gg_row);
  // The numeric setup.  uniform < 0: every indefinite piece shifted by its own
  // smallest decade (rod blocks, coarse matrix).  uniform >= 0: the DD of
  // H + uniform D (D = |diag H| floored per rod and on the interface), no other
  // shift; returns false on every rank if a rod block or the coarse matrix is then
  // not positive definite (only with the direct coarse solve).
  bool numeric(const TCrs &H, double uniform = -1.0);
  // The DD of H + sigma D for the smallest decade sigma that makes it positive
  // definite (DdOptions::uniform_shift; DdPreconditioner::setup); prev: the last
  // set-up's sigma (0: none), the first guess.
  void shift_uniformly(const TCrs &H, double prev);
  // numeric()'s steps.
  void assemble_interface(const double *vals, double uniform);
  bool condense_rods(const double *vals, double uniform, long long &shifted);
  void owned_coarse_graph();
  void sum_coarse_matrix();
  double uniform_shift = 0.0;     // of the last setup (0: none)
  std::vector<double> dg_uniform; // D_G of the uniform shift (per gg_diag entry)
  // dg_uniform made (on every rank at once: a rank without interface rows has an
  // empty one, so its emptiness cannot tell, and the first making is collective)
  bool dg_uniform_made = false;
  void apply(const TMV &X, TMV &Y, double alpha, double beta) const;
  double bytes() const;
};

void DdPreconditioner::Impl::build(const System &sys, const TCrs &H) {
  const DofBlocks &blk = sys.blocks();
  map = H.getRowMap();
  const size_t nloc = map->getNodeNumElements();
  if (blk.block.size() != nloc)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: DofBlocks do not match the map");
  const Numbering cn = number_coarse(blk, H);
  std::vector<std::vector<GO>> rod_gids;
  const std::vector<GO> ovg = build_rods(blk, H, cn, rod_gids);
  std::vector<std::pair<size_t, GO>> gg;
  std::vector<size_t> gg_row;
  coarse_graph(H, cn, ovg, rod_gids, gg, gg_row);
  locate_coarse_entries(rod_gids, gg, gg_row);
  S_built = false;
  nullspace = coarse_nullspace(cmap, blk, cn.slot, cn.node_points);
  bov = Teuchos::rcp(new TMV(cov, 1));
  yov = Teuchos::rcp(new TMV(cov, 1));
  b = Teuchos::rcp(new TMV(cmap, 1));
  y = Teuchos::rcp(new TMV(cmap, 1));
  t.assign(nloc, 0.0);
}

// The coarse numbering (Numbering): coarse_rows, cmap and iface_rows with it.
DdPreconditioner::Impl::Numbering
DdPreconditioner::Impl::number_coarse(const DofBlocks &blk, const TCrs &H) {
  auto comm = map->getComm();
  auto colmap = H.getColMap();
  const size_t nloc = map->getNodeNumElements(), ncol = colmap->getNodeNumElements();
  Numbering cn;
  const std::vector<int> &slot = cn.slot = coarse_nodes(blk, cn.node_points);
  const size_t nnodes = cn.node_points.size() / 3;
  const long long nif = cn.nif = 6LL * static_cast<long long>(nnodes);
  long long incl = 0;
  Teuchos::scan(*comm, Teuchos::REDUCE_SUM, nif, Teuchos::outArg(incl));
  const GO offset = cn.offset = static_cast<GO>(incl - nif);
  coarse_rows = sum_over_ranks(*comm, static_cast<long long>(blk.interface.size()));
  const long long padded = sum_over_ranks(*comm, nif);
  cmap = Teuchos::rcp(new TMap(static_cast<Tpetra::global_size_t>(padded),
                               static_cast<size_t>(nif), GO(0), comm));
  iface_rows.assign(static_cast<size_t>(nif), -1);
  TMV cg(map, 1);
  {
    auto v = cg.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < nloc; ++i) v(i, 0) = -1.0;
    for (size_t k = 0; k < blk.interface.size(); ++k) {
      const size_t c = static_cast<size_t>(slot[k]);
      iface_rows[c] = blk.interface[k].local;
      v(static_cast<size_t>(blk.interface[k].local), 0) =
          static_cast<double>(offset + GO(c));
    }
  }
  TMV cgc(colmap, 1); // coarse GID of every column (-1: a rod-interior DOF)
  cgc.doImport(cg, Tpetra::Import<>(map, colmap), Tpetra::INSERT);
  std::vector<GO> &ccol = cn.ccol;
  std::vector<LO> &col2row = cn.col2row;
  ccol.resize(ncol);
  col2row.resize(ncol);
  {
    auto v = cgc.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t c = 0; c < ncol; ++c) {
      ccol[c] = static_cast<GO>(v(c, 0));
      col2row[c] = map->getLocalElement(colmap->getGlobalElement(static_cast<LO>(c)));
    }
  }
  return cn;
}

// The rods: their interiors, bands and couplings to the interface (rod_gids: the
// coupled coarse GIDs of every rod, sorted), the entries between two rods' interiors
// (cross), and the overlapping coarse map cov (owned coarse rows, then the ghosts the
// rods couple to); returns cov's GIDs.
std::vector<GO>
DdPreconditioner::Impl::build_rods(const DofBlocks &blk, const TCrs &H,
                                   const Numbering &cn,
                                   std::vector<std::vector<GO>> &rod_gids) {
  auto comm = map->getComm();
  const size_t nloc = map->getNodeNumElements();
  const long long nif = cn.nif;
  const GO offset = cn.offset;
  // Rods: interiors, bands, couplings.
  rods.assign(static_cast<size_t>(blk.num_rods), Rod());
  std::vector<int> pos(nloc, -1);
  for (size_t i = 0; i < nloc; ++i)
    if (blk.block[i] >= 0) {
      Rod &r = rods.at(static_cast<size_t>(blk.block[i]));
      pos[i] = r.n();
      r.rows.push_back(static_cast<LO>(i));
    }
  auto lcl = H.getLocalMatrixHost();
  cross.clear();
  std::vector<GO> ghosts;
  rod_gids.assign(rods.size(), std::vector<GO>()); // coupled coarse GIDs, sorted
  for (size_t ir = 0; ir < rods.size(); ++ir) {
    scan_rod(ir, blk, lcl, cn, pos, rod_gids[ir]);
    for (GO g : rod_gids[ir])
      if (g < offset || g >= offset + nif) ghosts.push_back(g);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  std::vector<GO> ovg(static_cast<size_t>(nif));
  for (long long k = 0; k < nif; ++k) ovg[static_cast<size_t>(k)] = offset + GO(k);
  ovg.insert(ovg.end(), ghosts.begin(), ghosts.end());
  cov = Teuchos::rcp(new TMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                              Teuchos::ArrayView<const GO>(ovg.data(), ovg.size()), GO(0),
                              comm));
  return ovg;
}

// Rod ir's rows of H (pos: each owned DOF's position in its rod): its band, its
// couplings H_rG (coupled: their coarse GIDs, sorted) and the entries to other rods'
// interiors (cross).
void DdPreconditioner::Impl::scan_rod(size_t ir, const DofBlocks &blk,
                                      const TCrs::local_matrix_host_type &lcl,
                                      const Numbering &cn, const std::vector<int> &pos,
                                      std::vector<GO> &coupled) {
  const std::vector<GO> &ccol = cn.ccol;
  const std::vector<LO> &col2row = cn.col2row;
  Rod &r = rods[ir];
  std::vector<GO> bgid;
  for (int i = 0; i < r.n(); ++i) {
    const LO lr = r.rows[static_cast<size_t>(i)];
    for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
      const LO lc = lcl.graph.entries(q);
      if (ccol[static_cast<size_t>(lc)] >= 0) {
        coupled.push_back(ccol[static_cast<size_t>(lc)]);
        bgid.push_back(ccol[static_cast<size_t>(lc)]);
        r.b_row.push_back(i);
        r.b_src.push_back(q);
        continue;
      }
      const LO lr2 = col2row[static_cast<size_t>(lc)];
      if (lr2 == Teuchos::OrdinalTraits<LO>::invalid() ||
          blk.block[static_cast<size_t>(lr2)] != static_cast<int>(ir)) {
        // Another rod's interior: a structural zero of the pattern (rigid joints'
        // stencils are dense in it, their values are not); checked at every setup.
        cross.push_back(q);
        continue;
      }
      const int j = pos[static_cast<size_t>(lr2)];
      if (j <= i) {
        r.kd = std::max(r.kd, i - j);
        r.band_src.push_back(q);
        r.band_dst.push_back(static_cast<size_t>(i - j)); // column j added below
      }
    }
  }
  // band_dst = (i - j) + j (kd + 1): recompute with the final kd
  {
    size_t e = 0;
    for (int i = 0; i < r.n(); ++i) {
      const LO lr = r.rows[static_cast<size_t>(i)];
      for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
        if (e < r.band_src.size() && r.band_src[e] == q) {
          const size_t diff = r.band_dst[e];
          const size_t j = static_cast<size_t>(i) - diff;
          r.band_dst[e] = diff + j * static_cast<size_t>(r.kd + 1);
          ++e;
        }
      }
    }
  }
  std::sort(coupled.begin(), coupled.end());
  coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
  for (GO g : bgid)
    r.b_col.push_back(static_cast<int>(
        std::lower_bound(coupled.begin(), coupled.end(), g) - coupled.begin()));
}

// The graph of Sov (rows of cov): every rod's dense block, the H_GG entries; Sov on
// it.  gg: (H value index, column GID) of every H_GG entry, gg_row its owned row.
void DdPreconditioner::Impl::coarse_graph(const TCrs &H, const Numbering &cn,
                                          const std::vector<GO> &ovg,
                                          const std::vector<std::vector<GO>> &rod_gids,
                                          std::vector<std::pair<size_t, GO>> &gg,
                                          std::vector<size_t> &gg_row) {
  auto lcl = H.getLocalMatrixHost();
  const std::vector<GO> &ccol = cn.ccol;
  const GO offset = cn.offset;
  auto ov_local = [&](GO g) { return cov->getLocalElement(g); };
  std::vector<std::vector<GO>> rowcols(ovg.size());
  for (const auto &gids : rod_gids)
    for (GO a : gids)
      for (GO b2 : gids) rowcols[static_cast<size_t>(ov_local(a))].push_back(b2);
  gg.clear();
  gg_row.clear();
  for (size_t k = 0; k < iface_rows.size(); ++k) {
    const LO lr = iface_rows[k];
    rowcols[k].push_back(offset + GO(k)); // the diagonal always
    if (lr < 0) continue;                 // a dummy row: its diagonal only
    for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
      const GO c = ccol[static_cast<size_t>(lcl.graph.entries(q))];
      if (c < 0) continue;
      rowcols[k].push_back(c);
      gg.emplace_back(q, c);
      gg_row.push_back(k);
    }
  }
  std::vector<size_t> counts(ovg.size());
  for (size_t l = 0; l < ovg.size(); ++l) {
    auto &c = rowcols[l];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    counts[l] = c.size();
  }
  auto graph = Teuchos::rcp(new TCrs::crs_graph_type(
      cov, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (size_t l = 0; l < ovg.size(); ++l)
    graph->insertGlobalIndices(
        ovg[l], Teuchos::ArrayView<const GO>(rowcols[l].data(), rowcols[l].size()));
  rowcols.clear();
  rowcols.shrink_to_fit();
  graph->fillComplete(cmap, cmap);
  Sov = Teuchos::rcp(new TCrs(graph));
}

// Where every rod's block (r.coarse, r.s_pos) and every H_GG entry (gg_src, gg_dst,
// gg_diag) go in Sov's values; the export and import between cov and cmap.
void DdPreconditioner::Impl::locate_coarse_entries(
    const std::vector<std::vector<GO>> &rod_gids,
    const std::vector<std::pair<size_t, GO>> &gg, const std::vector<size_t> &gg_row) {
  auto ov_local = [&](GO g) { return cov->getLocalElement(g); };
  auto slcl = Sov->getLocalMatrixHost();
  auto scol = Sov->getColMap();
  for (size_t ir = 0; ir < rods.size(); ++ir) {
    Rod &r = rods[ir];
    const std::vector<GO> &gids = rod_gids[ir];
    const size_t m = gids.size();
    r.coarse.resize(m);
    r.s_pos.resize(m * m);
    for (size_t a = 0; a < m; ++a) {
      r.coarse[a] = ov_local(gids[a]);
      for (size_t b2 = 0; b2 < m; ++b2)
        r.s_pos[a * m + b2] =
            find_entry(slcl, r.coarse[a], scol->getLocalElement(gids[b2]));
    }
  }
  gg_src.clear();
  gg_dst.clear();
  for (size_t e = 0; e < gg.size(); ++e) {
    gg_src.push_back(gg[e].first);
    gg_dst.push_back(find_entry(slcl, static_cast<LO>(gg_row[e]),
                                scol->getLocalElement(gg[e].second)));
  }
  gg_diag.clear();
  dg_uniform.clear();
  dg_uniform_made = false;
  for (size_t e = 0; e < gg.size(); ++e)
    if (cov->getGlobalElement(static_cast<LO>(gg_row[e])) == gg[e].second)
      gg_diag.push_back(e);
  exporter = Teuchos::rcp(new Tpetra::Export<>(cov, cmap));
  importer = Teuchos::rcp(new Tpetra::Import<>(cmap, cov));
}

bool DdPreconditioner::Impl::numeric(const TCrs &H, double uniform) {
  auto comm = map->getComm();
  auto lcl = H.getLocalMatrixHost();
  const double *vals = lcl.values.data();
  assemble_interface(vals, uniform);
  bool coupled = false;
  for (size_t q : cross) coupled = coupled || vals[q] != 0.0;
  throw_if_any(
      *comm, coupled, RN_ERR_INTERNAL,
      "dd preconditioner: the Hessian couples the interiors of two rods (DofBlocks "
      "do not match the Hessian)");
  long long shifted = 0;
  const bool failed = condense_rods(vals, uniform, shifted);
  if (uniform >= 0.0) {
    int f = failed ? 1 : 0, any = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, f, Teuchos::outArg(any));
    if (any) {
      Sov->fillComplete(cmap, cmap);
      return false;
    }
  }
  throw_if_any(*comm, failed, RN_ERR_LAPACK,
               "dd preconditioner: a rod block has no positive definite shift up to 1e10 "
               "|diag| (non-finite entries?)");
  rods_shifted = sum_over_ranks(*comm, shifted);
  Sov->fillComplete(cmap, cmap);
  if (coarse_rows == 0) return true;
  if (!S_built) owned_coarse_graph();
  sum_coarse_matrix();
  coarse->set_strict(uniform >= 0.0);
  coarse->setup(S, nullspace);
  return !coarse->failed();
}

// Sov = H_GG (+ uniform D_G on the interface diagonal), the rods' contributions still
// to come (condense_rods); Sov left open for them.
void DdPreconditioner::Impl::assemble_interface(const double *vals, double uniform) {
  auto comm = map->getComm();
  Sov->resumeFill();
  Sov->setAllToScalar(0.0);
  auto sv = Sov->getLocalMatrixHost().values;
  for (size_t e = 0; e < gg_src.size(); ++e) sv(gg_dst[e]) += vals[gg_src[e]];
  if (uniform > 0.0) {
    // + uniform D_G on the interface diagonal, D_G = |diag H_GG| floored at 1e-8 of
    // its largest entry over the ranks at the first set-up that shifts uniformly,
    // then the entrywise largest |diag H_GG| of the set-ups since (as the rods' D_r)
    if (!dg_uniform_made) { // (collective: decided alike on every rank)
      dg_uniform_made = true;
      double mx = 0.0, gmx = 0.0;
      for (size_t e : gg_diag) mx = std::max(mx, std::fabs(vals[gg_src[e]]));
      Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, mx, Teuchos::outArg(gmx));
      dg_uniform.reserve(gg_diag.size());
      for (size_t e : gg_diag) {
        const double d = std::fabs(vals[gg_src[e]]);
        dg_uniform.push_back(gmx > 0.0 ? std::max(d, 1e-8 * gmx) : 1.0);
      }
    } else {
      for (size_t q = 0; q < gg_diag.size(); ++q)
        dg_uniform[q] = std::max(dg_uniform[q], std::fabs(vals[gg_src[gg_diag[q]]]));
    }
    for (size_t q = 0; q < gg_diag.size(); ++q)
      sv(gg_dst[gg_diag[q]]) += uniform * dg_uniform[q];
  }
  uniform_shift = uniform > 0.0 ? uniform : 0.0;
}

// Every rod block factored (shifted by uniform D_r with uniform >= 0, else by its own
// smallest decade if indefinite) and its Schur complement subtracted from Sov;
// shifted: the rods shifted.  True if a rod block could not be factored.
bool DdPreconditioner::Impl::condense_rods(const double *vals, double uniform,
                                           long long &shifted) {
  auto sv = Sov->getLocalMatrixHost().values;
  bool failed = false;
  std::vector<double> ab, Z, C;
  std::vector<int> first;
  for (Rod &r : rods) {
    r.b_val.resize(r.b_src.size());
    for (size_t e = 0; e < r.b_src.size(); ++e) r.b_val[e] = vals[r.b_src[e]];
    if (r.n() == 0) continue;
    if (!factor_rod(r, vals, ab, uniform)) {
      failed = true;
      continue;
    }
    shifted += r.shift > 0.0;
    if (r.m() == 0) continue;
    rod_schur(r, Z, first, C); // Sov -= H_Gr H_rr^-1 H_rG
    for (size_t e = 0; e < C.size(); ++e) sv(r.s_pos[e]) -= C[e];
  }
  return failed;
}

// The graph of the owned coarse rows once (S on it is refilled by summing the exported
// values into it: sum_coarse_matrix), S's diagonal positions and, without ghost rows,
// where each Sov value goes in S.
void DdPreconditioner::Impl::owned_coarse_graph() {
  auto comm = map->getComm();
  auto made = Tpetra::exportAndFillCompleteCrsMatrix<TCrs>(Sov, *exporter, cmap, cmap);
  S = Teuchos::rcp(new TCrs(made->getCrsGraph()));
  S_built = true;
  auto l = S->getLocalMatrixHost();
  sdiag.resize(iface_rows.size());
  for (size_t c = 0; c < sdiag.size(); ++c)
    sdiag[c] = find_entry(
        l, static_cast<LO>(c),
        S->getColMap()->getLocalElement(cmap->getGlobalElement(static_cast<LO>(c))));
  // Without ghost rows on any rank (one rank) the export is a copy: each Sov value's
  // S position once, instead of Tpetra's search by global index per value and
  // set-up (cubic in the row length: a rod in self contact has long coarse rows).
  int ghosted = cov->getNodeNumElements() > cmap->getNodeNumElements() ? 1 : 0, any = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, ghosted, Teuchos::outArg(any));
  s_copy.clear();
  if (!any) {
    auto ol = Sov->getLocalMatrixHost();
    auto ocol = Sov->getColMap(), scol = S->getColMap();
    s_copy.resize(ol.values.extent(0));
    for (LO row = 0; row < static_cast<LO>(ol.numRows()); ++row) {
      const LO srow = cmap->getLocalElement(cov->getGlobalElement(row));
      for (size_t q = ol.graph.row_map(row); q < ol.graph.row_map(row + 1); ++q)
        s_copy[q] = find_entry(
            l, srow, scol->getLocalElement(ocol->getGlobalElement(ol.graph.entries(q))));
    }
  }
}

// S = the sum of the ranks' Sov on the owned coarse rows; the dummy rows' diagonal.
void DdPreconditioner::Impl::sum_coarse_matrix() {
  S->resumeFill();
  S->setAllToScalar(0.0);
  if (!s_copy.empty()) {
    auto ov = Sov->getLocalMatrixHost().values;
    auto sv2 = S->getLocalMatrixHost().values;
    for (size_t q = 0; q < s_copy.size(); ++q) sv2(s_copy[q]) += ov(q);
  } else {
    S->doExport(*Sov, *exporter, Tpetra::ADD);
  }
  {
    // Dummy rows: 1e-6 of the mean |diagonal| of their node's real rows.  Decoupled,
    // they change nothing in the solution; small, they add almost no energy to the
    // coarse-level rigid modes that they carry (coarse_nodes).
    auto v = S->getLocalMatrixHost().values;
    for (size_t n = 0; n + 5 < iface_rows.size(); n += 6) {
      double sum = 0.0;
      int cnt = 0;
      for (size_t j = n; j < n + 6; ++j)
        if (iface_rows[j] >= 0) sum += std::fabs(v(sdiag[j])), ++cnt;
      const double d = cnt > 0 && sum > 0.0 ? 1e-6 * sum / cnt : 1.0;
      for (size_t j = n; j < n + 6; ++j)
        if (iface_rows[j] < 0) v(sdiag[j]) = d;
    }
  }
  S->fillComplete(cmap, cmap);
}

// The block at once: the rod solves column by column, then one export of the
// interface right-hand sides, one coarse solve and one import for all the columns
// (a block of LOBPCG costs the messages of one vector).
void DdPreconditioner::Impl::apply(const TMV &X, TMV &Y, double alpha,
                                   double beta) const {
  const size_t nloc = map->getNodeNumElements(), nc = X.getNumVectors();
  w.resize(nloc);
  t.resize(nloc * nc);
  auto x = X.getLocalViewHost(Tpetra::Access::ReadOnly);
  // 1. z_r = H_rr^-1 x_r, into t (column j at t + j nloc).
  for (size_t j = 0; j < nc; ++j) {
    double *tj = t.data() + j * nloc;
    for (const Rod &r : rods) {
      if (r.n() == 0) continue;
      double *z = w.data();
      for (int i = 0; i < r.n(); ++i)
        z[i] = x(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), j);
      solve_rod(r, z, 1);
      for (int i = 0; i < r.n(); ++i)
        tj[static_cast<size_t>(r.rows[static_cast<size_t>(i)])] = z[i];
    }
  }
  if (coarse_rows > 0) {
    ensure_columns(bov, cov, nc);
    ensure_columns(yov, cov, nc);
    ensure_columns(b, cmap, nc);
    ensure_columns(y, cmap, nc);
    // 2. b_G = x_G - sum_r H_Gr z_r (exported to the owners).
    {
      auto bv = bov->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t j = 0; j < nc; ++j) {
        const double *tj = t.data() + j * nloc;
        for (size_t l = 0; l < bv.extent(0); ++l) bv(l, j) = 0.0;
        for (size_t k = 0; k < iface_rows.size(); ++k)
          if (iface_rows[k] >= 0) bv(k, j) = x(static_cast<size_t>(iface_rows[k]), j);
        for (const Rod &r : rods)
          for (size_t e = 0; e < r.b_val.size(); ++e)
            bv(static_cast<size_t>(r.coarse[static_cast<size_t>(r.b_col[e])]), j) -=
                r.b_val[e] *
                tj[static_cast<size_t>(r.rows[static_cast<size_t>(r.b_row[e])])];
      }
    }
    b->putScalar(0.0);
    b->doExport(*bov, *exporter, Tpetra::ADD);
    // 3. coarse solve; 4. y_G to the ranks of the rods that touch it.
    coarse->solve(*b, *y);
    yov->doImport(*y, *importer, Tpetra::INSERT);
  }
  // 5. y_r = H_rr^-1 (x_r - H_rG y_G); interface rows y_G.
  auto out = Y.getLocalViewHost(Tpetra::Access::ReadWrite);
  auto yo = yov->getLocalViewHost(Tpetra::Access::ReadOnly);
  auto yc = y->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t j = 0; j < nc; ++j) {
    auto put = [&](size_t row, double v) {
      out(row, j) = beta == 0.0 ? alpha * v : beta * out(row, j) + alpha * v;
    };
    for (const Rod &r : rods) {
      if (r.n() == 0) continue;
      double *z = w.data();
      for (int i = 0; i < r.n(); ++i)
        z[i] = x(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), j);
      if (coarse_rows > 0)
        for (size_t e = 0; e < r.b_val.size(); ++e)
          z[r.b_row[e]] -=
              r.b_val[e] *
              yo(static_cast<size_t>(r.coarse[static_cast<size_t>(r.b_col[e])]), j);
      solve_rod(r, z, 1);
      for (int i = 0; i < r.n(); ++i)
        put(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), z[i]);
    }
    if (coarse_rows > 0)
      for (size_t k = 0; k < iface_rows.size(); ++k)
        if (iface_rows[k] >= 0) put(static_cast<size_t>(iface_rows[k]), yc(k, j));
  }
}

double DdPreconditioner::Impl::bytes() const {
  double b0 = 0.0;
  for (const Rod &r : rods)
    b0 += 8.0 * static_cast<double>(r.fac.size() + r.b_val.size() + r.s_pos.size()) +
          8.0 * static_cast<double>(r.band_src.size() + r.band_dst.size() +
                                    r.b_src.size()) +
          4.0 * static_cast<double>(r.rows.size() + r.coarse.size() + 2 * r.b_row.size());
  if (!Sov.is_null()) b0 += 12.0 * static_cast<double>(Sov->getNodeNumEntries());
  if (!S.is_null()) b0 += 12.0 * static_cast<double>(S->getNodeNumEntries());
  if (coarse) b0 += coarse->bytes();
  return b0;
}

namespace {

class DdOperator : public Tpetra::Operator<> {
public:
  explicit DdOperator(const Teuchos::RCP<const DdPreconditioner::Impl> &impl,
                      PreconditionerStats *stats)
      : impl_(impl), stats_(stats) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return impl_->map; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return impl_->map; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    const auto t0 = Clock::now();
    impl_->apply(X, Y, alpha, beta);
    stats_->applies++;
    stats_->apply_seconds += seconds_since(t0);
  }

private:
  Teuchos::RCP<const DdPreconditioner::Impl> impl_;
  PreconditionerStats *stats_;
};

// A = the coarse solver's SPD approximation of S: y = alpha A^{-1} x + beta y.
class CoarseInverse : public Tpetra::Operator<> {
public:
  explicit CoarseInverse(const Teuchos::RCP<const DdPreconditioner::Impl> &impl)
      : impl_(impl) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return impl_->cmap; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return impl_->cmap; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    if (X.getNumVectors() != 1 || Y.getNumVectors() != 1)
      throw Error(RN_ERR_INTERNAL,
                  "dd preconditioner: coarse inverse applied to a block");
    if (tmp_.is_null() || tmp_->getMap().get() != impl_->cmap.get())
      tmp_ = Teuchos::rcp(new TMV(impl_->cmap, 1));
    impl_->coarse->solve(X, *tmp_);
    Y.update(alpha, *tmp_, beta);
  }

private:
  Teuchos::RCP<const DdPreconditioner::Impl> impl_;
  mutable Teuchos::RCP<TMV> tmp_;
};

} // namespace

DdPreconditioner::DdPreconditioner(const DdOptions &opt) : opt_(opt), impl_(new Impl) {}
DdPreconditioner::~DdPreconditioner() = default;

namespace {

// The coarse solver the options ask for (Auto: the direct one, declining when it
// would cost more than opt.direct_max_flops, without limit where AMG cannot run: the
// serial runtime).
std::unique_ptr<CoarseSolver> make_coarse_solver(const DdOptions &opt, const Comm &comm) {
  switch (opt.coarse) {
  case DdOptions::Coarse::Direct:
    return make_direct_coarse_solver();
  case DdOptions::Coarse::Amg:
    return make_amg_coarse_solver(opt.amg_xml);
  case DdOptions::Coarse::Auto:
    break;
  }
  return make_direct_coarse_solver(mpi_backed(comm) ? opt.direct_max_flops : 0.0);
}

} // namespace

void DdPreconditioner::setup(System &sys) {
  const auto t0 = Clock::now();
  auto H = sys.hessian();
  if (H.is_null()) throw Error(RN_ERR_STATE, "dd preconditioner: no Hessian assembled");
  if (impl_->hgraph.get() != H->getCrsGraph().get()) {
    impl_->build(sys, *H);
    impl_->hgraph = H->getCrsGraph();
    impl_->coarse = make_coarse_solver(opt_, *H->getComm());
  }
  const double prev_uniform = impl_->uniform_shift; // the last set-up's (0: none)
  impl_->numeric(*H);
  if (opt_.uniform_shift && (impl_->rods_shifted > 0 || coarse_shift() > 0.0))
    impl_->shift_uniformly(*H, prev_uniform);
  if (impl_->coarse->declined() && mpi_backed(*H->getComm())) {
    // Auto: the direct factorisation costs too much
    impl_->declined_flops = impl_->coarse->flops();
    impl_->coarse = make_amg_coarse_solver(opt_.amg_xml);
    impl_->coarse->setup(impl_->S, impl_->nullspace);
  }
  stats_.setups++;
  stats_.setup_seconds += seconds_since(t0);
  stats_.bytes = impl_->bytes();
  stats_.shifted =
      impl_->rods_shifted > 0 || coarse_shift() > 0.0 || impl_->uniform_shift > 0.0;
}

// H indefinite (rod blocks or the coarse matrix): each piece shifted by its own
// decade, M would be the inverse of no single modification of H, and the trust
// region in its norm cycles; the coarse matrix alone shifted, S + t D_S, makes M
// nearly singular along the buckling mode (docs/solvers.md).  Instead the DD of
// H + sigma D for the smallest decade sigma that makes every rod block and (with
// the direct coarse solve) the coarse matrix positive definite: M = (H + sigma
// D)^-1 exactly, the factor preconditioner's norm.  D (D_r, D_G) is |diag H| of
// the first such set-up, raised entrywise to |diag H| of each later one, for the
// preconditioner's life (a load step): a metric that changes little from step to
// step, as the factor preconditioner's fixed one, but follows a structure that
// stiffens (a folded rod straightening; docs/solvers.md).  The multigrid coarse
// solve, which cannot certify, shifts S further itself if it must.
void DdPreconditioner::Impl::shift_uniformly(const TCrs &H, double prev) {
  const int hint = prev > 0.0 ? static_cast<int>(std::lround(std::log10(prev))) : 99;
  const double sigma =
      smallest_shift([&](double s) { return numeric(H, s); }, true, hint);
  if (sigma < 0.0)
    throw Error(RN_ERR_LAPACK, "dd preconditioner: no shift up to 1e10 |diag| makes "
                               "the Hessian positive definite (non-finite entries?)");
}

Teuchos::RCP<const Tpetra::Operator<>> DdPreconditioner::inverse() const {
  if (op_.is_null()) // one operator for the preconditioner's life (callers keep it)
    op_ = Teuchos::rcp(new DdOperator(impl_, const_cast<PreconditionerStats *>(&stats_)));
  return op_;
}

long long DdPreconditioner::coarse_rows() const { return impl_->coarse_rows; }
long long DdPreconditioner::rods_shifted() const { return impl_->rods_shifted; }
double DdPreconditioner::uniform_shift() const { return impl_->uniform_shift; }
double DdPreconditioner::coarse_shift() const {
  return impl_->coarse ? impl_->coarse->shift() : 0.0;
}
bool DdPreconditioner::exact() const {
  return impl_->rods_shifted == 0 && coarse_shift() == 0.0 &&
         impl_->uniform_shift == 0.0 &&
         (impl_->coarse_rows == 0 || coarse_solver() == "direct");
}

bool DdPreconditioner::coarse_pencil(Teuchos::RCP<const Tpetra::Operator<>> &S,
                                     Teuchos::RCP<const Tpetra::Operator<>> &Ainv) const {
  if (impl_->rods_shifted != 0 || coarse_shift() != 0.0 || impl_->uniform_shift != 0.0 ||
      impl_->coarse_rows == 0 || !impl_->coarse || impl_->S.is_null())
    return false;
  S = impl_->S;
  Ainv = Teuchos::rcp(new CoarseInverse(impl_));
  return true;
}

double DdPreconditioner::coarse_flops() const {
  const double f = impl_->coarse ? impl_->coarse->flops() : 0.0;
  return f > 0.0 ? f : impl_->declined_flops;
}

long long DdPreconditioner::coarse_separator_rows() const {
  return impl_->coarse ? impl_->coarse->separator_rows() : 0;
}

std::string DdPreconditioner::coarse_solver() const {
  return impl_->coarse ? impl_->coarse->name() : "none";
}

} // namespace rodnet
