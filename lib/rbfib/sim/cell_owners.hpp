#pragma once
// Cells on a split fluid (fluid/decomposition.hpp): each process steps the cells whose centroid
// lies in its planes; a cell whose centroid crosses into another process's planes moves there
// whole, with its index in the whole run, its data-site state and its body force. Checkpoints
// gather every cell in the order of those indices, so that they read the same whatever the
// number of processes.
#include "rbfib/cells/batch.hpp"

#include <array>
#include <memory>
#include <vector>

namespace rbfib::sim {

/// One cell as it travels between processes.
struct CellRecord {
  index_t id = 0;              ///< its index in the whole run's batch
  std::vector<double> state;   ///< 6 n_d: X then U at the data sites, component after component
  std::array<double, 3> body{0, 0, 0};  ///< its body force (dyn)
};

/// The cells of a batch as records (host copies), with their indices in the whole run.
std::vector<CellRecord> cell_records(const cells::Batch& batch, const std::vector<index_t>& ids);
/// A batch of these cells in the order given (none allowed).
cells::Batch batch_of(const std::shared_ptr<const cells::CellType>& type, const std::vector<CellRecord>& cells);
/// The state storage (n_d x 6N, as cells::Batch::state) of these cells in the order given.
std::vector<double> state_of(const std::vector<CellRecord>& cells, index_t n_data);
/// The cells of a whole batch's state storage, with indices 0..N-1 and the given body forces
/// (3N, F[d N + c]).
std::vector<CellRecord> records_of(const std::vector<double>& state, const std::vector<double>& body, index_t n_data);
/// The mean of the cell's data-site coordinates along `axis` (NaN if any is not finite).
double site_mean(const CellRecord& cell, int axis, index_t n_data);
/// The same for every cell of a batch, from its positions' `axis` block alone (one host copy of
/// n_d N values).
std::vector<double> site_means(const cells::Batch& batch, int axis);

/// Appends (batch, id, state, body) to a message; reads them back from a message of such entries.
void pack(const CellRecord& cell, index_t batch, std::vector<double>& message);
/// Calls add(batch, record) for every entry of the message.
template <class F>
void unpack(const std::vector<double>& message, const std::vector<index_t>& n_data, F&& add) {
  std::size_t at = 0;
  while (at < message.size()) {
    const index_t b = index_t(message[at]);
    CellRecord r;
    r.id = index_t(message[at + 1]);
    const std::size_t n = static_cast<std::size_t>(6 * n_data.at(static_cast<std::size_t>(b)));
    r.state.assign(message.begin() + std::ptrdiff_t(at + 2), message.begin() + std::ptrdiff_t(at + 2 + n));
    for (int d = 0; d < 3; ++d) r.body[d] = message[at + 2 + n + d];
    at += 2 + n + 3;
    add(b, std::move(r));
  }
}

}  // namespace rbfib::sim
