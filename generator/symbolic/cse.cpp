#include "generator/symbolic/cse.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>
#include <unordered_map>
#include <unordered_set>


namespace mbfe::gen {

namespace {

using GiNaC::ex;
using GiNaC::is_a;
using GiNaC::numeric;
using ExCount = std::unordered_map<ex, int, std::hash<ex>, GiNaC::ex_is_equal>;
using ExMap = std::unordered_map<ex, ex, std::hash<ex>, GiNaC::ex_is_equal>;

bool is_compound(const ex& e) {
  return GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e) || GiNaC::is_a<GiNaC::power>(e) ||
         GiNaC::is_a<GiNaC::function>(e);
}

// The order CSE visits operands in, independent of memory addresses: a
// structural key with GiNaC's own symbol names. It is not the sign-folding
// key of CodeList::canonical (code_list.h): a canonical form must treat e and
// -e alike, a visit order need not, and the temporaries' numbering of every
// committed solver follows this one, so the two stay apart.
std::string structural_key(const ex& e) {
  std::ostringstream out;
  if (is_a<GiNaC::symbol>(e)) return GiNaC::ex_to<GiNaC::symbol>(e).get_name();
  if (is_a<numeric>(e)) {
    out << e;
    return out.str();
  }
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < e.nops(); ++i) parts.push_back(structural_key(e.op(i)));
  if (is_a<GiNaC::add>(e) || is_a<GiNaC::mul>(e)) std::sort(parts.begin(), parts.end());
  std::string head = is_a<GiNaC::add>(e)     ? "+"
                     : is_a<GiNaC::mul>(e)   ? "*"
                     : is_a<GiNaC::power>(e) ? "^"
                     : is_a<GiNaC::function>(e) ? GiNaC::ex_to<GiNaC::function>(e).get_name()
                                                : "?";
  std::string text = head + "(";
  for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? "," : "") + parts[i];
  return text + ")";
}


std::vector<ex> operands_in_structural_order(const ex& e) {
  std::vector<std::pair<std::string, ex>> keyed;
  for (std::size_t i = 0; i < e.nops(); ++i) keyed.emplace_back(structural_key(e.op(i)), e.op(i));
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<ex> out;
  for (auto& item : keyed) out.push_back(item.second);
  return out;
}

// Counts occurrences; a node's children are counted only on its first visit,
// so a repeated subtree hoists once, not together with all of its parts.
void count(const ex& e, ExCount& counts) {
  if (!is_compound(e)) return;
  if (++counts[e] > 1) return;
  for (std::size_t i = 0; i < e.nops(); ++i) count(e.op(i), counts);
}

// Replaces each operand by its rewritten form (GiNaC's map() wants a map_function).
struct OperandLookup : GiNaC::map_function {
  explicit OperandLookup(const ExMap& m) : rewritten(m) {}
  ex operator()(const ex& e) override {
    const auto it = rewritten.find(e);
    return it == rewritten.end() ? e : it->second;
  }
  const ExMap& rewritten;
};

class Rewriter {
 public:
  Rewriter(const ExCount& counts, std::vector<Assignment>& out) : counts_(counts), out_(out) {}

  ex rewrite(const ex& e) {
    if (!is_compound(e)) return e;
    if (auto it = hoisted_.find(e); it != hoisted_.end()) return it->second;
    ExMap children;
    for (const ex& child : operands_in_structural_order(e)) children.emplace(child, rewrite(child));
    OperandLookup lookup(children);
    const ex rebuilt = e.map(lookup);
    const auto c = counts_.find(e);
    if (c == counts_.end() || c->second < 2) return rebuilt;
    GiNaC::symbol temp("cse" + std::to_string(added_++));
    out_.push_back({temp, rebuilt});
    hoisted_.emplace(e, temp);
    return temp;
  }
  int added() const { return added_; }

 private:
  const ExCount& counts_;
  std::vector<Assignment>& out_;
  ExMap hoisted_;
  int added_ = 0;
};

}  // namespace

int eliminate_common_subexpressions(Kernel& kernel) {
  ExCount counts;
  for (const auto& s : kernel.statements) count(s.rhs, counts);
  for (const auto& o : kernel.outputs) count(o.value, counts);
  std::vector<Assignment> statements;
  Rewriter rewriter(counts, statements);
  for (const auto& s : kernel.statements) {
    const ex rhs = rewriter.rewrite(s.rhs);
    statements.push_back({s.lhs, rhs});
  }
  for (auto& o : kernel.outputs) o.value = rewriter.rewrite(o.value);

  // A statement left holding a bare symbol (its whole value was hoisted, or was
  // a copy to begin with) is a copy: substitute it forward instead of printing it.
  GiNaC::exmap aliases;
  kernel.statements.clear();
  for (auto& s : statements) {
    const ex rhs = aliases.empty() ? s.rhs : s.rhs.subs(aliases);
    if (is_atomic(rhs)) {
      aliases[s.lhs] = rhs;
      continue;
    }
    kernel.statements.push_back({s.lhs, rhs});
  }
  if (!aliases.empty())
    for (auto& o : kernel.outputs) o.value = o.value.subs(aliases);
  return rewriter.added();
}

}  // namespace mbfe::gen
