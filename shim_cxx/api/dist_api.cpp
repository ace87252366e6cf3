// dist_api.cpp - extern "C" helpers of distributed solves (rodnet_solve.h): ranks,
// agreement on statuses and messages, partition sizes.  MPI only (no Trilinos), so
// that the command's MPI paths stay in the shim.
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <list>
#include <string>
#include <vector>

#include "rodnet_solve.h"

namespace {

bool mpi_up() {
  int up = 0, down = 0;
  MPI_Initialized(&up);
  MPI_Finalized(&down);
  return up && !down;
}

// A notice as sent: RN_DIST_NOTICE_INTS ints then the text (NUL-terminated), one
// MPI_BYTE message of tag kNoticeTag; kept until its send has completed.
constexpr int kNoticeTag = 7301;
constexpr size_t kNoticeBytes = RN_DIST_NOTICE_INTS * sizeof(int) + RN_DIST_NOTICE_TEXT;
struct Pending {
  std::vector<char> buf;
  MPI_Request req = MPI_REQUEST_NULL;
};
std::list<Pending> &pending() {
  static std::list<Pending> p;
  return p;
}
// Drops the records whose sends have completed.
void reap(bool wait) {
  auto &p = pending();
  for (auto it = p.begin(); it != p.end();) {
    int done = 1;
    if (wait)
      MPI_Wait(&it->req, MPI_STATUS_IGNORE);
    else
      MPI_Test(&it->req, &done, MPI_STATUS_IGNORE);
    it = done ? p.erase(it) : std::next(it);
  }
}

// v[0 .. n-1] reduced in place over MPI_COMM_WORLD (rn_dist_allreduce_*).
template <class T>
rn_status allreduce(T *v, int n, int op, MPI_Datatype type) {
  if (n < 0 || (n > 0 && !v) || op < RN_DIST_SUM || op > RN_DIST_MIN) return RN_ERR_ARG;
  int size = 1;
  if (mpi_up()) MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size == 1 || n == 0) return RN_OK;
  const MPI_Op mop = op == RN_DIST_SUM ? MPI_SUM : op == RN_DIST_MAX ? MPI_MAX : MPI_MIN;
  return MPI_Allreduce(MPI_IN_PLACE, v, n, type, mop, MPI_COMM_WORLD) == MPI_SUCCESS
             ? RN_OK
             : RN_ERR_INTERNAL;
}

} // namespace

extern "C" {

void rn_runtime_ranks(int *rank, int *size) {
  int r = 0, s = 1;
  if (mpi_up()) {
    MPI_Comm_rank(MPI_COMM_WORLD, &r);
    MPI_Comm_size(MPI_COMM_WORLD, &s);
  }
  if (rank) *rank = r;
  if (size) *size = s;
}

rn_status rn_dist_agree(rn_context *ctx, rn_status local) {
  int rank = 0, size = 1;
  rn_runtime_ranks(&rank, &size);
  if (size == 1) return local;
  try {
    int mine = local != RN_OK ? rank : size, first = size;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size) return RN_OK;
    std::string text;
    if (rank == first && ctx) text = rn_context_last_error(ctx);
    int len = static_cast<int>(text.size()), st = local;
    MPI_Bcast(&len, 1, MPI_INT, first, MPI_COMM_WORLD);
    MPI_Bcast(&st, 1, MPI_INT, first, MPI_COMM_WORLD);
    text.resize(static_cast<size_t>(len));
    if (len) MPI_Bcast(&text[0], len, MPI_CHAR, first, MPI_COMM_WORLD);
    if (ctx && rank != first)
      rn_context_set_error(ctx, static_cast<rn_status>(st), "rank %d: %s", first,
                           text.c_str());
    return static_cast<rn_status>(st);
  } catch (...) {
    return RN_ERR_INTERNAL;
  }
}

rn_status rn_dist_allreduce_int(int *v, int n, int op) {
  return allreduce(v, n, op, MPI_INT);
}

rn_status rn_dist_allreduce_double(double *v, int n, int op) {
  return allreduce(v, n, op, MPI_DOUBLE);
}

rn_status rn_dist_notice_send(const int *v, int n, const char *text) {
  if (n < 0 || n > RN_DIST_NOTICE_INTS || (n > 0 && !v)) return RN_ERR_ARG;
  int rank = 0, size = 1;
  rn_runtime_ranks(&rank, &size);
  if (size == 1 || rank == 0) return RN_OK;
  try {
    reap(false);
    Pending rec;
    rec.buf.assign(kNoticeBytes, 0);
    std::memcpy(rec.buf.data(), v, static_cast<size_t>(n) * sizeof(int));
    if (text) {
      const size_t len = std::min(std::strlen(text), size_t{RN_DIST_NOTICE_TEXT} - 1);
      std::memcpy(rec.buf.data() + RN_DIST_NOTICE_INTS * sizeof(int), text, len);
    }
    auto &p = pending();
    p.push_back(std::move(rec));
    Pending &b = p.back();
    if (MPI_Isend(b.buf.data(), static_cast<int>(kNoticeBytes), MPI_BYTE, 0, kNoticeTag,
                  MPI_COMM_WORLD, &b.req) != MPI_SUCCESS) {
      p.pop_back();
      return RN_ERR_INTERNAL;
    }
    return RN_OK;
  } catch (const std::bad_alloc &) {
    return RN_ERR_ALLOC;
  } catch (...) {
    return RN_ERR_INTERNAL;
  }
}

int rn_dist_notice_poll(int *v, int n, char *text, size_t text_size, int *from) {
  int rank = 0, size = 1;
  rn_runtime_ranks(&rank, &size);
  if (size == 1 || rank != 0 || n < 0 || n > RN_DIST_NOTICE_INTS || (n > 0 && !v))
    return 0;
  int flag = 0;
  MPI_Status status;
  if (MPI_Iprobe(MPI_ANY_SOURCE, kNoticeTag, MPI_COMM_WORLD, &flag, &status) !=
          MPI_SUCCESS ||
      !flag)
    return 0;
  try {
    std::vector<char> buf(kNoticeBytes, 0);
    if (MPI_Recv(buf.data(), static_cast<int>(kNoticeBytes), MPI_BYTE, status.MPI_SOURCE,
                 kNoticeTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE) != MPI_SUCCESS)
      return 0;
    std::memcpy(v, buf.data(), static_cast<size_t>(n) * sizeof(int));
    if (text && text_size > 0) {
      const char *t = buf.data() + RN_DIST_NOTICE_INTS * sizeof(int);
      const size_t len = std::min(strnlen(t, RN_DIST_NOTICE_TEXT - 1), text_size - 1);
      std::memcpy(text, t, len);
      text[len] = '\0';
    }
    if (from) *from = status.MPI_SOURCE;
    return 1;
  } catch (...) {
    return 0;
  }
}

rn_status rn_dist_notice_flush(void) {
  try {
    reap(true);
    return RN_OK;
  } catch (...) {
    return RN_ERR_INTERNAL;
  }
}

rn_status rn_dist_part_sizes(const rn_network *net, int *ranks, long *owned_dofs,
                             long *owned_stencils) {
  int rank = 0, size = 1;
  rn_part_info info;
  if (!net || !ranks) return RN_ERR_ARG;
  rn_runtime_ranks(&rank, &size);
  *ranks = size;
  if (!owned_dofs) return RN_OK;
  const rn_status st = rn_network_part_info(net, &info);
  long mine[2] = {st == RN_OK ? static_cast<long>(info.owned_dofs) : -1,
                  st == RN_OK ? info.owned_stencils : -1};
  std::vector<long> all(2 * static_cast<size_t>(size));
  if (size > 1)
    MPI_Allgather(mine, 2, MPI_LONG, all.data(), 2, MPI_LONG, MPI_COMM_WORLD);
  else
    all.assign(mine, mine + 2);
  rn_status out = st;
  for (int q = 0; q < size; ++q) {
    if (all[2 * static_cast<size_t>(q)] < 0) out = RN_ERR_STATE;
    owned_dofs[q] = all[2 * static_cast<size_t>(q)];
    if (owned_stencils) owned_stencils[q] = all[2 * static_cast<size_t>(q) + 1];
  }
  return out;
}

rn_status rn_dist_gather_state(const rn_network *part, rn_network *whole) {
  int rank = 0, size = 1;
  rn_runtime_ranks(&rank, &size);
  if (!part) return RN_ERR_ARG;
  try {
    size_t n = 0;
    rn_status st = rn_network_part_state_pack(part, nullptr, &n);
    std::vector<double> mine(st == RN_OK ? n : 1, 0.0);
    if (st == RN_OK) st = rn_network_part_state_pack(part, mine.data(), &n);
    if (st != RN_OK) mine.assign(1, 0.0); // no records
    int cnt = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<size_t>(size), 0),
        disp(static_cast<size_t>(size) + 1, 0);
    if (size > 1)
      MPI_Gather(&cnt, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    else
      counts[0] = cnt;
    for (int q = 0; q < size; ++q)
      disp[static_cast<size_t>(q) + 1] =
          disp[static_cast<size_t>(q)] + counts[static_cast<size_t>(q)];
    std::vector<double> all(
        rank == 0 ? static_cast<size_t>(disp[static_cast<size_t>(size)]) : 1);
    if (size > 1)
      MPI_Gatherv(mine.data(), cnt, MPI_DOUBLE, all.data(), counts.data(), disp.data(),
                  MPI_DOUBLE, 0, MPI_COMM_WORLD);
    else
      all = mine;
    if (rank == 0 && st == RN_OK) {
      if (!whole) return RN_ERR_ARG;
      for (int q = 0; q < size && st == RN_OK; ++q)
        st = rn_network_part_state_unpack(
            whole, all.data() + disp[static_cast<size_t>(q)],
            static_cast<size_t>(counts[static_cast<size_t>(q)]));
    }
    return st;
  } catch (const std::bad_alloc &) {
    return RN_ERR_ALLOC;
  } catch (...) {
    return RN_ERR_INTERNAL;
  }
}

} // extern "C"
