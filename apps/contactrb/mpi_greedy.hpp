#pragma once
// `mpirun -np K contactrb offline --greedy ...`: the MPI side of offline::GreedyDistribution
// (docs/parallel.md). Every rank runs the greedy and builds the same models; each sweeps the
// estimate over its equal block of the training set (rank_block), MPI_Allgatherv gives every
// rank all the estimates in point order, so every rank picks the serial run's points; a step's
// HF solves are shared out (point k of the step on rank k mod K: rank 0 alone with --greedy-batch
// 1) and every rank's snapshots are gathered by every rank (bit for bit, snapshot_wire.hpp), so
// every rank holds the serial run's snapshot set.
#include "contactrb/offline/offline_greedy.hpp"
#include "mpi_world.hpp"

namespace contactrb::app {

// The distribution over `world` (which must outlive the greedy run).
offline::GreedyDistribution mpi_greedy_distribution(MpiWorld& world);

}  // namespace contactrb::app
