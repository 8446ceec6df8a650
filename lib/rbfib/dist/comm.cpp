#include "rbfib/dist/comm.hpp"

#include "rbfib/core/error.hpp"

#include <fftw3-mpi.h>

namespace rbfib::dist {

Traffic& traffic() {
  static Traffic t;
  return t;
}

void check(int mpi_result, const std::string& what) {
  if (mpi_result == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(mpi_result, text, &length);
  throw NumericalError(Cause::solver, what + ": MPI error: " + std::string(text, static_cast<std::size_t>(length)));
}

Session::Session(int& argc, char**& argv) {
  int provided = MPI_THREAD_SINGLE;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED)
    throw NumericalError(Cause::solver, "MPI: this library offers no MPI_THREAD_FUNNELED (OpenMP teams inside a rank need it)");
  // Errors come back as codes (check() turns them into exceptions), not as an abort inside MPI.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  // FFTW's threads first, then its MPI transforms (FFTW 3.3 manual, sec. 6.11).
  fftw_init_threads();
  fftw_mpi_init();
}

Session::~Session() {
  fftw_mpi_cleanup();
  MPI_Finalize();
}

Comm::Comm(MPI_Comm comm) : comm_(comm) {
  check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
}

namespace {
template <class T>
T reduce(MPI_Comm comm, T v, MPI_Datatype type, MPI_Op op) {
  T out{};
  ++traffic().reductions;
  check(MPI_Allreduce(&v, &out, 1, type, op, comm), "MPI_Allreduce");
  return out;
}
}  // namespace

double Comm::sum(double v) const { return reduce(comm_, v, MPI_DOUBLE, MPI_SUM); }
double Comm::max(double v) const { return reduce(comm_, v, MPI_DOUBLE, MPI_MAX); }
index_t Comm::sum(index_t v) const {
  static_assert(sizeof(index_t) == sizeof(long long));
  return static_cast<index_t>(reduce(comm_, static_cast<long long>(v), MPI_LONG_LONG, MPI_SUM));
}
bool Comm::all(bool ok) const { return reduce(comm_, ok ? 1 : 0, MPI_INT, MPI_LAND) != 0; }

std::vector<std::vector<double>> Comm::exchange(const std::vector<std::vector<double>>& to) const {
  require(int(to.size()) == size_, "Comm::exchange: messages", to.size(), "must be one per rank, " + to_text(size_));
  std::vector<int> send_counts(size_), recv_counts(size_), send_at(size_, 0), recv_at(size_, 0);
  for (int q = 0; q < size_; ++q) send_counts[q] = int(to[q].size());
  check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm_), "MPI_Alltoall");
  std::vector<double> send, recv;
  for (int q = 0; q < size_; ++q) {
    send_at[q] = int(send.size());
    send.insert(send.end(), to[q].begin(), to[q].end());
    if (q != rank_) traffic().cells += double(to[q].size() * sizeof(double));
  }
  int total = 0;
  for (int q = 0; q < size_; ++q) recv_at[q] = total, total += recv_counts[q];
  recv.resize(static_cast<std::size_t>(total));
  check(MPI_Alltoallv(send.data(), send_counts.data(), send_at.data(), MPI_DOUBLE, recv.data(), recv_counts.data(),
                      recv_at.data(), MPI_DOUBLE, comm_),
        "MPI_Alltoallv");
  std::vector<std::vector<double>> from(static_cast<std::size_t>(size_));
  for (int q = 0; q < size_; ++q) from[q].assign(recv.begin() + recv_at[q], recv.begin() + recv_at[q] + recv_counts[q]);
  return from;
}

namespace {
void broadcast(MPI_Comm comm, int root, std::string& s) {
  int length = static_cast<int>(s.size());
  check(MPI_Bcast(&length, 1, MPI_INT, root, comm), "MPI_Bcast");
  s.resize(static_cast<std::size_t>(length));
  check(MPI_Bcast(s.data(), length, MPI_CHAR, root, comm), "MPI_Bcast");
}
}  // namespace

void Comm::agree(std::exception_ptr error) const {
  const int failed = reduce(comm_, error ? rank_ : size_, MPI_INT, MPI_MIN);
  if (failed == size_) return;
  int what[2] = {2, 0};  // kind (0 input, 1 numerical, 2 other), cause
  std::string field, text;
  if (rank_ == failed) {
    try {
      std::rethrow_exception(error);
    } catch (const InputError& e) {
      what[0] = 0, field = e.field(), text = e.what();
    } catch (const NumericalError& e) {
      what[0] = 1, what[1] = int(e.cause()), text = e.what();
    } catch (const std::exception& e) {
      text = e.what();
    }
  }
  check(MPI_Bcast(what, 2, MPI_INT, failed, comm_), "MPI_Bcast");
  broadcast(comm_, failed, field);
  broadcast(comm_, failed, text);
  if (rank_ == failed) std::rethrow_exception(error);
  if (what[0] == 0) {  // "field = value: why"
    const std::string rest = text.size() > field.size() + 3 ? text.substr(field.size() + 3) : text;
    const std::size_t colon = rest.find(": ");
    throw InputError(field, rest.substr(0, colon), colon == std::string::npos ? "" : rest.substr(colon + 2));
  }
  if (what[0] == 1) throw NumericalError(Cause(what[1]), text);
  throw std::runtime_error(text);
}

}  // namespace rbfib::dist
