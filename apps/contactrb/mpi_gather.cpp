#include "mpi_gather.hpp"

#include <algorithm>
#include <climits>

#include "contactrb/common/error.hpp"

#if CONTACTRB_HAVE_MPI
#include <mpi.h>
#endif

namespace contactrb::app {

std::pair<std::size_t, std::size_t> rank_block(std::size_t n, int rank, int size) {
  const auto r = static_cast<std::size_t>(rank), k = static_cast<std::size_t>(size);
  return {n / k * r + std::min(r, n % k), n / k * (r + 1) + std::min(r + 1, n % k)};
}

#if CONTACTRB_HAVE_MPI

void gather_blocks(MpiWorld& world, const std::vector<std::vector<double>*>& columns) {
  if (world.size() == 1) return;
  for (std::vector<double>* c : columns) {
    const std::size_t n = c->size();
    std::vector<int> counts, displs;
    for (int r = 0; r < world.size(); ++r) {
      const auto [b, e] = rank_block(n, r, world.size());
      require(e - b < static_cast<std::size_t>(INT_MAX) && b < static_cast<std::size_t>(INT_MAX),
              "more than 2^31 items in one MPI gather");
      counts.push_back(static_cast<int>(e - b));
      displs.push_back(static_cast<int>(b));
    }
    const auto [b, e] = rank_block(n, world.rank(), world.size());
    if (world.rank() == 0) {
      MPI_Gatherv(MPI_IN_PLACE, 0, MPI_DOUBLE, c->data(), counts.data(), displs.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
    } else {
      MPI_Gatherv(c->data() + b, static_cast<int>(e - b), MPI_DOUBLE, nullptr, nullptr, nullptr, MPI_DOUBLE, 0,
                  MPI_COMM_WORLD);
    }
  }
}

#else

void gather_blocks(MpiWorld& world, const std::vector<std::vector<double>*>&) {
  require(world.size() == 1, "internal: MPI gather in a build without MPI");
}

#endif

}  // namespace contactrb::app
