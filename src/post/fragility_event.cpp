// The event expression of a fragility curve (post/fragility_event.hpp): a tokenizer and a
// recursive-descent parser for
//
//     expression := conjunction { "or" conjunction }
//     conjunction := term { "and" term }
//     term := "(" expression ")" | NAME (">" | ">=" | "<" | "<=") NUMBER
#include "adjoin/post/fragility_event.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "adjoin/core/errors.hpp"
#include "adjoin/core/parse_number.hpp"

namespace adjoin {
namespace {

struct Token {
  enum Kind { name, number, comparison, open, close, end, bad } kind;
  std::string text;
  std::size_t at;  // 1-based character position
};

bool name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ':' || c == '-';
}
bool number_char(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-';
}

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    const std::size_t start = i;
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    Token::Kind kind = Token::bad;
    if (c == '(' || c == ')') {
      kind = c == '(' ? Token::open : Token::close;
      ++i;
    } else if (c == '<' || c == '>' || c == '=' || c == '!') {
      while (i < text.size() && (text[i] == '<' || text[i] == '>' || text[i] == '=' || text[i] == '!')) ++i;
      const std::string op = text.substr(start, i - start);
      kind = op == ">" || op == ">=" || op == "<" || op == "<=" ? Token::comparison : Token::bad;
    } else if (name_start(c)) {
      while (i < text.size() && name_char(text[i])) ++i;
      kind = Token::name;
    } else if (number_char(c)) {
      while (i < text.size() && number_char(text[i])) ++i;
      kind = Token::number;
    } else {
      ++i;
    }
    tokens.push_back({kind, text.substr(start, i - start), start + 1});
  }
  tokens.push_back({Token::end, "", text.size() + 1});
  return tokens;
}

// User text in a message: printable and short.
std::string in_quotes(const std::string& text) {
  std::string out;
  for (char c : text.substr(0, 60)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  return "\"" + out + (text.size() > 60 ? "...\"" : "\"");
}

}  // namespace

class EventParser {
 public:
  EventParser(FragilityEvent& event, const std::vector<std::string>& columns)
      : event_(event), columns_(columns), tokens_(tokenize(event.text_)) {}

  int expression() {
    int left = conjunction();
    while (is_keyword("or")) {
      ++next_;
      left = join(FragilityEvent::Op::or_, left, conjunction());
    }
    return left;
  }

  void expect_end() {
    if (tokens_[next_].kind != Token::end) fail("expected `and`, `or` or the end");
  }

 private:
  using Op = FragilityEvent::Op;

  int conjunction() {
    int left = term();
    while (is_keyword("and")) {
      ++next_;
      left = join(Op::and_, left, term());
    }
    return left;
  }

  int term() {
    const Token& t = tokens_[next_];
    if (t.kind == Token::open) {
      ++next_;
      const int inner = expression();
      if (tokens_[next_].kind != Token::close) fail("expected `)`");
      ++next_;
      return inner;
    }
    if (t.kind != Token::name || t.text == "and" || t.text == "or")
      fail("expected a column name (a comparison reads COLUMN > NUMBER)");
    const auto column = std::find(columns_.begin(), columns_.end(), t.text);
    if (column == columns_.end()) {
      std::string list;
      for (const std::string& c : columns_) list += (list.empty() ? "" : ", ") + c;
      throw InputError(prefix() + "no column " + in_quotes(t.text) + " (at character " + std::to_string(t.at) +
                       "); the table has: " + list);
    }
    ++next_;
    const Token& op = tokens_[next_];
    if (op.kind != Token::comparison)
      fail("expected one of > >= < <= after " + t.text + " (a true/false column reads as 1/0: " + t.text + " > 0)");
    ++next_;
    const Token& value = tokens_[next_];
    double number = 0.0;
    if (value.kind != Token::number || parse_number(value.text, number) != NumberStatus::ok)
      fail("expected a finite number after " + t.text + " " + op.text);
    ++next_;
    FragilityEvent::Node node{comparison(op.text), static_cast<std::size_t>(column - columns_.begin()), number};
    event_.nodes_.push_back(node);
    return static_cast<int>(event_.nodes_.size()) - 1;
  }

  static Op comparison(const std::string& op) {
    return op == ">" ? Op::greater : op == ">=" ? Op::greater_equal : op == "<" ? Op::less : Op::less_equal;
  }

  int join(Op op, int left, int right) {
    FragilityEvent::Node node{op};
    node.left = left;
    node.right = right;
    event_.nodes_.push_back(node);
    return static_cast<int>(event_.nodes_.size()) - 1;
  }

  bool is_keyword(const char* word) const {
    return tokens_[next_].kind == Token::name && tokens_[next_].text == word;
  }

  std::string prefix() const { return event_.option_ + " " + in_quotes(event_.text_) + ": "; }

  [[noreturn]] void fail(const std::string& expected) const {
    const Token& t = tokens_[next_];
    const std::string found = t.kind == Token::end ? "the end" : in_quotes(t.text) + " at character " + std::to_string(t.at);
    throw InputError(prefix() + expected + ", found " + found);
  }

  FragilityEvent& event_;
  const std::vector<std::string>& columns_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

FragilityEvent FragilityEvent::parse(const std::string& text, const std::vector<std::string>& columns,
                                     const std::string& option) {
  FragilityEvent event;
  event.text_ = text;
  event.option_ = option;
  EventParser parser(event, columns);
  event.root_ = parser.expression();
  parser.expect_end();
  return event;
}

std::optional<bool> FragilityEvent::evaluate(const std::vector<double>& values) const { return evaluate(root_, values); }

std::optional<bool> FragilityEvent::evaluate(int index, const std::vector<double>& values) const {
  const Node& n = nodes_[static_cast<std::size_t>(index)];
  if (n.op == Op::and_ || n.op == Op::or_) {
    const std::optional<bool> a = evaluate(n.left, values), b = evaluate(n.right, values);
    const bool decisive = n.op == Op::or_;  // the value that settles it whatever the other says
    if (a == decisive || b == decisive) return decisive;
    if (!a || !b) return std::nullopt;
    return !decisive;
  }
  const double v = values.at(n.column);
  if (std::isnan(v)) return std::nullopt;
  switch (n.op) {
    case Op::greater: return v > n.number;
    case Op::greater_equal: return v >= n.number;
    case Op::less: return v < n.number;
    default: return v <= n.number;
  }
}

std::vector<std::size_t> FragilityEvent::columns_used() const {
  std::vector<std::size_t> used;
  for (const Node& n : nodes_)
    if (n.op != Op::and_ && n.op != Op::or_ && std::find(used.begin(), used.end(), n.column) == used.end())
      used.push_back(n.column);
  return used;
}

FragilityOutcomes fragility_outcomes(const FragilityEvent& event, const std::vector<std::string>& records,
                                     const std::vector<double>& im, const std::vector<std::vector<double>>& values,
                                     const std::vector<std::string>& errors) {
  FragilityOutcomes out;
  std::vector<double> row(values.size(), std::nan(""));
  std::vector<FragilityRun> every;
  for (std::size_t r = 0; r < records.size(); ++r) {
    every.push_back({records[r], im[r], false});
    if (!errors.empty() && !errors[r].empty()) {
      ++out.failed;
      continue;
    }
    for (std::size_t c : event.columns_used()) row[c] = values[c][r];
    const std::optional<bool> happened = event.evaluate(row);
    if (!happened) {
      if (out.unknown++ == 0) out.first_unknown = r;
      continue;
    }
    out.runs.push_back({records[r], im[r], *happened});
  }
  out.trace = fragility_is_trace(every);
  return out;
}

}  // namespace adjoin
