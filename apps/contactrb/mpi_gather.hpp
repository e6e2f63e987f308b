#pragma once
// Static blocks of n items over the MPI ranks, and their gathering to rank 0 (`contactrb
// sample` under mpirun: online queries cost about the same, so equal blocks balance).
#include <cstddef>
#include <utility>
#include <vector>

#include "mpi_world.hpp"

namespace contactrb::app {

// [begin, end) of rank `rank`'s block of n items (sizes differ by at most one).
std::pair<std::size_t, std::size_t> rank_block(std::size_t n, int rank, int size);

// Every column has n entries on every rank, rank r having filled its block; afterwards rank 0
// holds every block (the other ranks' columns are unchanged). Nothing to do for one rank.
void gather_blocks(MpiWorld& world, const std::vector<std::vector<double>*>& columns);

}  // namespace contactrb::app
