#include "batch_lines.hpp"

#include <memory>
#include <ostream>
#include <vector>

#include "contactrb/common/error.hpp"
#include "contactrb/rb/online_many.hpp"

namespace contactrb::app {

int answer_batch_lines(const rb::ReducedModel& model, const rb::OnlineSizes& sizes, int jobs, const ReadLine& read,
                       const AnswerLine& answer, std::ostream& out) {
  require(jobs >= 1, "--jobs must be >= 1 (got " + std::to_string(jobs) + ")");
  const std::size_t chunk = jobs == 1 ? 1 : static_cast<std::size_t>(jobs) * 64;
  struct Line {
    std::string text;
    bool too_long = false;
    std::string answer;
  };
  std::vector<Line> lines(chunk);
  std::vector<std::unique_ptr<rb::OnlineSolver>> solvers;  // one per thread, for the whole batch
  for (int j = 0; j < jobs; ++j) solvers.push_back(std::make_unique<rb::OnlineSolver>(model, sizes));
  int k = 0;
  for (bool more = true; more;) {
    std::size_t m = 0;
    while (m < chunk && (more = read(lines[m].text, lines[m].too_long))) ++m;
    if (m == 0) break;
    const int first = k + 1;
    rb::for_each_query(solvers, m, [&](rb::OnlineSolver& solver, std::size_t i) {
      lines[i].answer = answer(solver, first + static_cast<int>(i), lines[i].text, lines[i].too_long);
    }, 4);
    for (std::size_t i = 0; i < m; ++i) out << lines[i].answer << '\n';
    out.flush();  // answers stream through pipes
    k += static_cast<int>(m);
  }
  return k;
}

}  // namespace contactrb::app
