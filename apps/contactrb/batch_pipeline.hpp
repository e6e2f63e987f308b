#pragma once
// `online --batch --jobs J` without MPI (batch_lines.hpp): a pipeline of three stages that run
// at the same time, so that the J solver threads never wait for the reading or the printing.
//  - the calling thread reads chunks of lines (up to `depth` chunks read and not yet printed);
//  - J worker threads, one solver each, answer the lines of the oldest chunks, a few lines at a
//    time from a shared counter: each thread parses, solves and formats its lines;
//  - a printer thread writes each chunk's answers (and their messages, on stderr), in input
//    order, once the whole chunk is answered, and flushes (answers stream through a pipe, a chunk at a time). It does not wait
//    for the reader: a chunk is printed even while the next one waits for its input.
// The first exception (of the reader, a worker or the printer) stops every stage and is
// rethrown once every thread has stopped; a reader waiting for input stops after that line.
#include <cstddef>
#include <iosfwd>
#include <memory>
#include <vector>

#include "batch_lines.hpp"
#include "contactrb/online/online_solver.hpp"

namespace contactrb::app {

// Lines answered by solvers.size() threads (>= 1), chunk lines read at a time (>= 1).
BatchCounts pipeline_batch_lines(const std::vector<std::unique_ptr<online::OnlineSolver>>& solvers, std::size_t chunk,
                                 const ReadLine& read, const AnswerLine& answer, std::ostream& out);

}  // namespace contactrb::app
