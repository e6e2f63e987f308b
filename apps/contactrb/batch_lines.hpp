#pragma once
// `online --batch --jobs J` (docs/cluster.md): batch lines answered on J threads, one online
// solver each, and printed in input order. The lines are read in chunks (J x 64 lines): a
// chunk's answers are printed, and flushed, once the whole chunk is answered, so answers still
// stream through a pipe. With J = 1 every line is answered and printed before the next is read
// (the serial behaviour).
#include <functional>
#include <iosfwd>
#include <streambuf>
#include <string>

#include "contactrb/rb/online_solver.hpp"
#include "contactrb/rb/reduced_model.hpp"

namespace contactrb::app {

// Reads the next line into `line` (setting `too_long`); false at the end of the input.
using ReadLine = std::function<bool(std::string& line, bool& too_long)>;
// The output line of input line k (1-based), without its '\n'. Called concurrently for
// different k with the calling thread's solver: it may touch only what belongs to line k (or
// lock).
using AnswerLine = std::function<std::string(rb::OnlineSolver& solver, int k, const std::string& line, bool too_long)>;

// Returns the number of lines read.
int answer_batch_lines(const rb::ReducedModel& model, const rb::OnlineSizes& sizes, int jobs, const ReadLine& read,
                       const AnswerLine& answer, std::ostream& out);

}  // namespace contactrb::app
