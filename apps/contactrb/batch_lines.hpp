#pragma once
// `online --batch --jobs J` (docs/parallel.md): batch lines answered on J threads, one online
// solver each, and printed in input order. The lines are read in chunks (J x 64 lines, times
// the number of MPI ranks): a chunk's answers are printed, and flushed, once the whole chunk is
// answered, so answers still stream through a pipe. With J = 1 and no MPI every line is
// answered and printed before the next is read (the serial behaviour).
//
// Under mpirun (`world` given): rank 0 reads the chunk and sends it to every rank, each rank
// answers an equal block of it on its J threads, and rank 0 gathers the answers and prints them.
#include <functional>
#include <iosfwd>
#include <string>

#include "contactrb/online/online_solver.hpp"
#include "contactrb/model/reduced_model.hpp"
#include "mpi_world.hpp"

namespace contactrb::app {

// Reads the next line into `line` (setting `too_long`); false at the end of the input. Called
// on rank 0 only.
using ReadLine = std::function<bool(std::string& line, bool& too_long)>;

// The answer to one line: its output bytes (a text line with its '\n', or a binary row),
// printed as they are, and what to count.
struct LineAnswer {
  std::string text;
  std::string message;         // for stderr (with its '\n'), printed in input order with the text
  bool bad = false;            // the line could not be answered
  bool not_converged = false;  // answered, without convergence
};
// The answer to input line k (1-based). Called concurrently for different k with the calling
// thread's solver: it may touch only what belongs to line k (or lock).
using AnswerLine =
    std::function<LineAnswer(online::OnlineSolver& solver, int k, const std::string& line, bool too_long)>;

struct BatchCounts {
  int lines = 0;
  int bad = 0;
  int not_converged = 0;
};

// jobs: threads (0: every hardware thread). The counts over every rank (on rank 0; the other ranks' own counts elsewhere).
BatchCounts answer_batch_lines(const contactrb::model::ReducedModel& model, const online::OnlineSizes& sizes, int jobs,
                               const ReadLine& read, const AnswerLine& answer, std::ostream& out,
                               MpiWorld* world = nullptr);

}  // namespace contactrb::app
