// The IR's text form (specs/ir.md): reading, writing, round trips, and the reader's diagnostics.
#include <gtest/gtest.h>

#include <climits>

#include "ir_support.hpp"
#include "semo/semantics/ir_text.hpp"

namespace semo {
namespace {

using ir::Expr;
using ir::Op;

struct Read {
  SourceManager sources;
  DiagnosticEngine diags{sources};
  std::optional<ir::Model> model;
  // "line:col: message" of the first error, for readable assertions.
  [[nodiscard]] std::string firstError() const {
    for (const Diagnostic& d : diags.diagnostics()) {
      if (d.severity == Severity::Error) {
        return std::to_string(d.range.begin.line) + ":" + std::to_string(d.range.begin.column) + ": " + d.message;
      }
    }
    return "";
  }
};

std::unique_ptr<Read> read(const std::string& text) {
  auto r = std::make_unique<Read>();
  FileId file = r->sources.add("test.ir", text);
  r->model = ir::parseText(r->sources, file, r->diags);
  return r;
}

ir::Model parse(const std::string& text) {
  auto r = read(text);
  EXPECT_TRUE(r->model.has_value()) << r->firstError() << "\nin:\n" << text;
  return r->model ? *r->model : ir::Model{};
}

// The expression of the only invariant of `semo-ir 1; var ...; invariant e : <expr>;`.
Expr invariantExpr(const std::string& vars, const std::string& expr) {
  ir::Model m = parse("semo-ir 1;\n" + vars + "\ninvariant e : " + expr + ";\n");
  return m.invariants.empty() ? Expr{} : m.invariants[0].holds;
}

// A compact prefix form of an expression, to assert the shape of a parse.
std::string shape(const ir::Model& m, const Expr& e) {
  switch (e.op) {
    case Op::Const: return std::to_string(e.value);
    case Op::Var: return m.variables.at(static_cast<ir::VarId>(e.value)).name;
    default: break;
  }
  static const char* names[] = {"const", "var", "not", "neg", "add", "sub", "mul", "div", "mod", "min", "max",
                                "eq",    "ne",  "lt",  "le",  "gt",  "ge",  "and", "or",  "implies", "ite"};
  std::string out = std::string("(") + names[static_cast<int>(e.op)];
  for (const Expr& a : e.args) out += " " + shape(m, a);
  return out + ")";
}

// ---- round trips

void expectRoundTrip(const ir::Model& m) {
  std::string once = ir::toText(m);
  auto r = read(once);
  ASSERT_TRUE(r->model.has_value()) << r->firstError() << "\nin the writer's output:\n" << once;
  EXPECT_EQ(ir::toText(*r->model), once);
}

TEST(IrText, RoundTripOfAHandWrittenModel) {
  ir::Model m = parse(R"(semo-ir 1;
robots scout1 scout2;
assume "robots crash at most once";
assume "quotes \" and backslashes \\ survive";

var scout1.mode : 0..3 = 1 @robot(scout1) @values("idle search found crashed");
var scout2.mode : 0..3 @robot(scout2);
var ok : bool = true;
var heading : -180..180 = -90;
var slot[3] : 0..2 = 2;

rule scout1.search @robot(scout1) @kind(step) @origin("mission.semo:12:5") @label("starts \"searching\"") @fair :
  scout1.mode == 0 && ok -> scout1.mode' = 1, heading' = -heading;
rule lose @kind(loss) : slot[0] != slot[1] -> 0.9 : slot[0]' = slot[1] + 0.1 : skip;
rule crash @robot(scout2) @kind(crash) : scout2.mode != 3 -> scout2.mode' = 3;
rule tick @kind(timer) : true -> slot[2]' = (slot[2] + 1) % 3, ok' = !ok;
rule env @kind(environment) : heading > 0 => ok ? heading < 90 : heading >= -90 -> heading' = max(-180, min(180, heading * 2 / 3 - 1));
rule deliver @kind(delivery) : true -> 0.25 : skip + 0.5 : ok' = false + 0.25 : ok' = true, slot[1]' = 0;

invariant heading_in_range @origin("mission.semo:30:1") : -180 <= heading && heading <= 180;
invariant implications : (ok => scout1.mode != 3) => (scout2.mode == 3 || !ok);
valid_end : scout1.mode == 3 || scout2.mode == 3;
)");
  expectRoundTrip(m);
  EXPECT_EQ(m.assumptions.at(1), "quotes \" and backslashes \\ survive");
  EXPECT_EQ(m.rules.at(0).label, "starts \"searching\"");
}

TEST(IrText, RoundTripOfEveryOperatorAndNesting) {
  ir::Model m;
  m.variables.push_back({"a", -5, 5, 0, false, ir::kNoRobot, {}, {}});
  m.variables.push_back({"b", 0, 1, 1, true, ir::kNoRobot, {}, {}});
  Expr a = Expr::var(0), b = Expr::var(1);
  std::vector<Expr> exprs;
  for (Op op : {Op::Add, Op::Sub, Op::Mul, Op::Div, Op::Mod, Op::Min, Op::Max, Op::Eq, Op::Ne, Op::Lt, Op::Le,
                Op::Gt, Op::Ge, Op::And, Op::Or, Op::Implies}) {
    exprs.push_back(Expr::binary(op, a, b));
    exprs.push_back(Expr::binary(op, Expr::binary(op, a, b), b));  // left nesting
    exprs.push_back(Expr::binary(op, a, Expr::binary(op, b, a)));  // right nesting
    exprs.push_back(Expr::binary(op, Expr::ite(b, a, b), Expr::unary(Op::Neg, Expr::binary(Op::Sub, a, b))));
  }
  exprs.push_back(Expr::ite(Expr::ite(b, b, b), Expr::ite(b, a, a), Expr::ite(b, a, a)));
  exprs.push_back(Expr::unary(Op::Not, Expr::unary(Op::Not, b)));
  exprs.push_back(Expr::unary(Op::Neg, Expr::unary(Op::Neg, a)));
  exprs.push_back(Expr::unary(Op::Neg, Expr::constant(-5)));
  exprs.push_back(Expr::binary(Op::Sub, a, Expr::constant(-5)));
  exprs.push_back(Expr::binary(Op::Mul, Expr::constant(INT32_MIN), Expr::constant(INT32_MAX)));
  for (std::size_t i = 0; i < exprs.size(); ++i) m.invariants.push_back({"e" + std::to_string(i), "", exprs[i]});
  expectRoundTrip(m);
}

TEST(IrText, RoundTripKeepsTheExpressionTrees) {
  // Not only the same text: reading the writer's output gives the same trees, so the writer's
  // parentheses are where the precedences need them.
  ir::Model m;
  m.variables.push_back({"x", -9, 9, 0, false, ir::kNoRobot, {}, {}});
  Expr x = Expr::var(0);
  m.invariants.push_back({"i1", "", Expr::binary(Op::Sub, x, Expr::binary(Op::Sub, x, x))});
  m.invariants.push_back({"i2", "", Expr::binary(Op::Implies, Expr::binary(Op::Implies, x, x), x)});
  m.invariants.push_back({"i3", "", Expr::ite(Expr::binary(Op::Implies, x, x), Expr::ite(x, x, x), Expr::binary(Op::Or, x, x))});
  m.invariants.push_back({"i4", "", Expr::binary(Op::Mul, Expr::binary(Op::Add, x, x), Expr::unary(Op::Not, Expr::binary(Op::Eq, x, x)))});
  auto r = read(ir::toText(m));
  ASSERT_TRUE(r->model.has_value()) << r->firstError();
  for (std::size_t i = 0; i < m.invariants.size(); ++i) {
    EXPECT_EQ(shape(*r->model, r->model->invariants[i].holds), shape(m, m.invariants[i].holds)) << ir::toText(m);
  }
}

TEST(IrText, RoundTripOfProbabilities) {
  // Small probabilities are written with a decimal point (never 1e-05), so that the reader tells
  // `+ 0.00001 :` (the next outcome) from an addition.
  ir::Model m;
  m.variables.push_back({"x", 0, 3, 0, false, ir::kNoRobot, {}, {}});
  ir::Rule r;
  r.name = "flip";
  r.guard = Expr::constant(1);
  for (double p : {0.1, 0.2, 0.69999, 0.00001}) {
    r.branches.push_back({p, {{0, Expr::binary(Op::Add, Expr::var(0), Expr::constant(1))}}});
  }
  m.rules.push_back(r);
  std::string text = ir::toText(m);
  EXPECT_NE(text.find("+ 0.00001 : x' = x + 1"), std::string::npos) << text;
  auto back = read(text);
  ASSERT_TRUE(back->model.has_value()) << back->firstError() << "\n" << text;
  ASSERT_EQ(back->model->rules.at(0).branches.size(), 4u);
  EXPECT_DOUBLE_EQ(back->model->rules[0].branches[3].probability, 0.00001);
  EXPECT_EQ(ir::toText(*back->model), text);
}

TEST(IrText, RoundTripOfNamesThatAreNotNameTokens) {
  // Names with spaces or brackets (as the translation gives invariants), array elements that differ
  // (so that they cannot be written back as one array), and strings with line breaks.
  ir::Model m;
  m.robots = {"r"};
  m.variables.push_back({"pc[0]", 0, 3, 0, false, 0, {}, {}});
  m.variables.push_back({"pc[1]", 0, 3, 2, false, 0, {}, {}});  // another initial value
  m.variables.push_back({"pc[2]", 0, 3, 2, false, 0, {}, {}});
  m.variables.push_back({"q[0]", 0, 1, 0, true, ir::kNoRobot, {}, {}});
  m.variables.push_back({"q[1]", 0, 1, 0, true, ir::kNoRobot, {}, {}});
  ir::Rule r;
  r.name = "step [r] #1";
  r.label = "two\nlines, \"quoted\"";
  r.guard = Expr::binary(Op::Lt, Expr::var(1), Expr::var(2));
  r.branches.push_back({1.0, {{2, Expr::var(1)}}});
  m.rules.push_back(r);
  m.invariants.push_back({"group_formation[Search group (Burger)]", "m.semo:1:1", Expr::var(3)});
  m.invariants.push_back({"true", "", Expr::var(4)});
  std::string text = ir::toText(m);
  EXPECT_NE(text.find("var \"pc[0]\" : 0..3 = 0 @robot(r);\nvar \"pc[1]\" : 0..3 = 2 @robot(r);\nvar \"pc[2]\""),
            std::string::npos) << text;
  EXPECT_NE(text.find("var q[2] : bool = false;"), std::string::npos) << text;
  EXPECT_NE(text.find("invariant \"group_formation[Search group (Burger)]\" @origin"), std::string::npos) << text;
  auto back = read(text);
  ASSERT_TRUE(back->model.has_value()) << back->firstError() << "\n" << text;
  EXPECT_EQ(ir::toText(*back->model), text);
  const ir::Model& b = *back->model;
  ASSERT_EQ(b.variables.size(), 5u);
  EXPECT_EQ(b.variables[1].name, "pc[1]");
  EXPECT_EQ(b.variables[1].init, 2);
  EXPECT_EQ(b.rules.at(0).name, "step [r] #1");
  EXPECT_EQ(b.rules[0].label, "two\nlines, \"quoted\"");
  EXPECT_EQ(b.invariants.at(0).name, "group_formation[Search group (Burger)]");
  EXPECT_EQ(b.invariants.at(1).name, "true");
}

TEST(IrText, RoundTripOfEveryShippedModel) {
  std::size_t models = test::forEachShippedModel([](const std::string&, const std::string& text) { expectRoundTrip(parse(text)); });
  EXPECT_GE(models, 8u);
}

// ---- reading

TEST(IrText, ReadsDeclarationsAndAttributes) {
  ir::Model m = parse(R"(semo-ir 1   # the ';' after the version may be left out
robots a b;
var a.mode : 0..2 = 1 @robot(b) @values("idle  busy done");
var flag : bool = true;
var t : -3..-1;
rule go @robot(a) @kind(crash) @origin("m.semo:1:2") @label("goes") @fair : flag -> a.mode' = 2, flag' = false;
invariant i @origin("m.semo:3:4") : t < 0;
valid_end : true;
)");
  ASSERT_EQ(m.robots, (std::vector<std::string>{"a", "b"}));
  ASSERT_EQ(m.variables.size(), 3u);
  const ir::Variable& mode = m.variables[0];
  EXPECT_EQ(mode.name, "a.mode");
  EXPECT_EQ(mode.init, 1);
  EXPECT_EQ(mode.robot, 1);
  EXPECT_EQ(mode.valueNames, (std::vector<std::string>{"idle", "busy", "done"}));
  EXPECT_TRUE(m.variables[1].isBool);
  EXPECT_EQ(m.variables[1].init, 1);
  EXPECT_EQ(m.variables[2].min, -3);
  EXPECT_EQ(m.variables[2].max, -1);
  EXPECT_EQ(m.variables[2].init, -3) << "the initial value defaults to min";
  const ir::Rule& go = m.rules.at(0);
  EXPECT_EQ(go.robot, 0);
  EXPECT_EQ(go.kind, ir::RuleKind::Crash);
  EXPECT_EQ(go.origin.text(), "m.semo:1:2");
  EXPECT_EQ(go.origin.line, 1u);
  EXPECT_EQ(go.origin.column, 2u);
  EXPECT_EQ(go.origin.file, "m.semo");
  EXPECT_EQ(go.label, "goes");
  EXPECT_TRUE(go.weaklyFair);
  ASSERT_EQ(go.branches.size(), 1u);
  EXPECT_EQ(go.branches[0].probability, 1.0);
  ASSERT_EQ(go.branches[0].assignments.size(), 2u);
  EXPECT_EQ(go.branches[0].assignments[1].var, 1u);
  EXPECT_EQ(m.invariants.at(0).origin, "m.semo:3:4");
  ASSERT_TRUE(m.validEnd.has_value());
  EXPECT_TRUE(m.validEnd->isTrue());
}

TEST(IrText, ArraysAreFlattened) {
  ir::Model m = parse(R"(semo-ir 1;
robots r;
var a[3] : 0..2 = 1 @robot(r);
var b : bool;
rule set : a[2] == 1 -> a[0]' = a[2] + 1, a[1]' = 0;
)");
  ASSERT_EQ(m.variables.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    const ir::Variable& v = m.variables[static_cast<std::size_t>(i)];
    EXPECT_EQ(v.name, "a[" + std::to_string(i) + "]");
    EXPECT_EQ(v.min, 0);
    EXPECT_EQ(v.max, 2);
    EXPECT_EQ(v.init, 1);
    EXPECT_EQ(v.robot, 0);
  }
  EXPECT_EQ(m.find("a[1]"), 1u);
  EXPECT_EQ(m.find("b"), 3u);
  EXPECT_FALSE(m.find("a").has_value());
  EXPECT_EQ(shape(m, m.rules.at(0).guard), "(eq a[2] 1)");
  EXPECT_EQ(m.rules[0].branches[0].assignments[0].var, 0u);
  EXPECT_EQ(m.rules[0].branches[0].assignments[1].var, 1u);
  EXPECT_EQ(read("semo-ir 1;\nvar a[3] : 0..2;\ninvariant i : a[3] == 0;\n")->firstError(),
            "3:15: undeclared variable 'a[3]'");
}

TEST(IrText, Precedence) {
  const std::string vars = "var a : bool; var b : bool; var c : bool; var x : 0..9; var y : 0..9;";
  ir::Model m = parse("semo-ir 1;\n" + vars);
  auto s = [&](const std::string& e) { return shape(m, invariantExpr(vars, e)); };
  // ?: is the loosest, and right-associative
  EXPECT_EQ(s("a ? x : b ? y : 0"), "(ite a x (ite b y 0))");
  EXPECT_EQ(s("a => b ? x : y"), "(ite (implies a b) x y)");
  EXPECT_EQ(s("a ? b => c : c"), "(ite a (implies b c) c)");
  EXPECT_EQ(s("a ? x : a => b"), "(ite a x (implies a b))");
  // => is right-associative, and looser than ||
  EXPECT_EQ(s("a => b => c"), "(implies a (implies b c))");
  EXPECT_EQ(s("a || b => c && a"), "(implies (or a b) (and c a))");
  EXPECT_EQ(s("(a => b) => c"), "(implies (implies a b) c)");
  // then || && == < + * and unary, left-associative
  EXPECT_EQ(s("a || b && c"), "(or a (and b c))");
  EXPECT_EQ(s("a && x == y"), "(and a (eq x y))");
  EXPECT_EQ(s("x == y < 3"), "(eq x (lt y 3))");
  EXPECT_EQ(s("x < y + 1"), "(lt x (add y 1))");
  EXPECT_EQ(s("x + y * 2"), "(add x (mul y 2))");
  EXPECT_EQ(s("x - y - 1"), "(sub (sub x y) 1)");
  EXPECT_EQ(s("x / y % 2"), "(mod (div x y) 2)");
  EXPECT_EQ(s("-x * !a"), "(mul (neg x) (not a))");
  EXPECT_EQ(s("!a == b"), "(eq (not a) b)");
  EXPECT_EQ(s("min(x, y + 1) <= max(x, 2 * y)"), "(le (min x (add y 1)) (max x (mul 2 y)))");
  EXPECT_EQ(s("true && !false"), "(and 1 (not 0))");
  // the writer puts back exactly the parentheses that are needed
  EXPECT_EQ(ir::toText(m, invariantExpr(vars, "(a ? x : y) + (x - (y - 1)) * 2")), "(a ? x : y) + (x - (y - 1)) * 2");
  EXPECT_EQ(ir::toText(m, invariantExpr(vars, "((a => b) => c) ? (a ? b : c) : a => b")),
            "(a => b) => c ? (a ? b : c) : a => b");
}

TEST(IrText, ProbabilisticOutcomesWithAssignments) {
  // `+` after an outcome's last assignment starts the next outcome (a probability is a decimal).
  ir::Model m = parse(R"(semo-ir 1;
var x : 0..3;
var y : 0..3;
rule r : true -> 0.75 : x' = y + 1, y' = 2 + 0.25 : x' = 0;
)");
  const ir::Rule& r = m.rules.at(0);
  ASSERT_EQ(r.branches.size(), 2u);
  EXPECT_DOUBLE_EQ(r.branches[0].probability, 0.75);
  EXPECT_EQ(shape(m, r.branches[0].assignments[0].value), "(add y 1)");
  EXPECT_EQ(shape(m, r.branches[0].assignments[1].value), "2");
  EXPECT_DOUBLE_EQ(r.branches[1].probability, 0.25);
  EXPECT_EQ(r.branches[1].assignments.size(), 1u);
}

TEST(IrText, ProbabilitiesAsFractionsAreKeptExactAndWrittenBackAsFractions) {
  // 1/27 has no exact decimal: the fraction is kept, and `+ 1/27 :` starts the next outcome.
  ir::Model m = parse("semo-ir 1;\nvar x : 0..3;\nrule r : true -> 26/27 : x' = x / 2 + 1/27 : x' = 3;\n");
  const ir::Rule& r = m.rules.at(0);
  ASSERT_EQ(r.branches.size(), 2u);
  EXPECT_EQ(shape(m, r.branches[0].assignments[0].value), "(div x 2)");
  EXPECT_EQ(r.branches[1].numerator, 1u);
  EXPECT_EQ(r.branches[1].denominator, 27u);
  EXPECT_DOUBLE_EQ(r.branches[1].probability, 1.0 / 27.0);
  const std::string text = ir::toText(m);
  EXPECT_NE(text.find("+ 1/27 : x' = 3"), std::string::npos) << text;
  EXPECT_EQ(ir::toText(parse(text)), text);
  // Many outcomes (a synchronous round of ten coin flips) are read; `check` refuses more than 256.
  std::string many = "semo-ir 1;\nvar x : 0..1023;\nrule r : true ->";
  for (int o = 0; o < 1024; ++o) many += (o == 0 ? " " : " + ") + std::string("1/1024 : x' = ") + std::to_string(o);
  EXPECT_EQ(parse(many + ";\n").rules.at(0).branches.size(), 1024u);
}

TEST(IrText, ExtremeIntegers) {
  ir::Model m = parse("semo-ir 1;\nvar x : -2147483648..2147483647 = -2147483648;\ninvariant i : x >= -2147483648;\n");
  ASSERT_EQ(m.variables.size(), 1u);
  EXPECT_EQ(m.variables[0].min, INT32_MIN);
  EXPECT_EQ(m.variables[0].init, INT32_MIN);
  EXPECT_EQ(shape(m, m.invariants.at(0).holds), "(ge x -2147483648)");
  EXPECT_EQ(read("semo-ir 1;\nvar x : 0..2147483648;\n")->firstError(), "2:12: integer out of range");
}

// ---- errors, with their exact positions

struct BadInput {
  const char* what;
  const char* text;
  const char* error;  // "line:col: message"
};
void PrintTo(const BadInput& b, std::ostream* os) { *os << b.what; }  // a stable name (mission_support.hpp)

class IrReaderErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(IrReaderErrors, ReportsTheFirstErrorAtItsPosition) {
  auto r = read(GetParam().text);
  EXPECT_FALSE(r->model.has_value());
  EXPECT_EQ(r->firstError(), GetParam().error);
}

INSTANTIATE_TEST_SUITE_P(
    IrText, IrReaderErrors,
    ::testing::Values(
        BadInput{"undeclared_variable", "semo-ir 1;\nvar x : 0..3;\nrule r : x > 0 && y -> x' = 0;\n",
                 "3:19: undeclared variable 'y'"},
        BadInput{"undeclared_target", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> z' = 0;\n",
                 "3:18: undeclared variable 'z'"},
        BadInput{"init_out_of_range", "semo-ir 1;\nvar x : 0..3 = 4;\n", "2:5: initial value 4 is outside the range"},
        BadInput{"negative_init_out_of_range", "semo-ir 1;\nvar t : -3..-1 = 0;\n", "2:5: initial value 0 is outside the range"},
        BadInput{"probabilities_not_one", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 0.5 : x' = 1 + 0.4 : x' = 2;\n",
                 "3:45: the probabilities of rule 'r' add up to 0.900000, not 1"},
        BadInput{"single_probability_not_one", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 0.5 : x' = 1;\n",
                 "3:30: the probabilities of rule 'r' add up to 0.500000, not 1"},
        BadInput{"probability_above_one", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 1.5 : x' = 1;\n",
                 "3:18: a probability must be in (0, 1]"},
        BadInput{"fraction_above_one", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 3/2 : x' = 1;\n",
                 "3:18: a probability must be in (0, 1]"},
        BadInput{"fraction_over_zero", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 1/0 : x' = 1;\n",
                 "3:20: a probability's denominator must not be 0"},
        BadInput{"fractions_not_one", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> 1/3 : x' = 1 + 1/3 : x' = 2;\n",
                 "3:45: the probabilities of rule 'r' add up to 0.666667, not 1"},
        BadInput{"unknown_attribute", "semo-ir 1;\nvar x : 0..3 @colour(red);\n", "2:15: unknown attribute '@colour' here"},
        BadInput{"attribute_in_wrong_place", "semo-ir 1;\nvar x : 0..3;\ninvariant i @fair : x > 0;\n",
                 "3:14: unknown attribute '@fair' here"},
        BadInput{"duplicate_variable", "semo-ir 1;\nvar x : 0..3;\nvar y : bool;\nvar x : bool;\n",
                 "4:5: variable 'x' is declared twice"},
        BadInput{"duplicate_array_element", "semo-ir 1;\nvar a[1] : 0..3;\nvar a[2] : bool;\n",
                 "3:5: variable 'a[0]' is declared twice"},
        BadInput{"missing_semicolon", "semo-ir 1;\nvar x : 0..3\nvar y : 0..3;\n",
                 "3:1: expected ';' after the variable declaration, found 'var'"},
        BadInput{"missing_semicolon_after_rule", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> x' = 1\n",
                 "4:1: expected ';' after the rule, found end of file"},
        BadInput{"bad_version", "semo-ir 2;\n", "1:9: unsupported IR version 2 (this semo reads version 1)"},
        BadInput{"not_an_ir_file", "var x : 0..3;\n", "1:1: expected 'semo-ir' at the start of an IR file, found 'var'"},
        BadInput{"unknown_robot", "semo-ir 1;\nrobots a b;\nvar x : 0..3 @robot(c);\n",
                 "3:15: unknown robot 'c' (declare it with 'robots ...;')"},
        BadInput{"duplicate_robot", "semo-ir 1;\nrobots a b;\nrobots c a;\n", "3:10: robot 'a' is declared twice"},
        BadInput{"duplicate_rule", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> skip;\nrule r : x > 0 -> skip;\n",
                 "4:6: rule 'r' is declared twice"},
        BadInput{"duplicate_invariant", "semo-ir 1;\nvar x : 0..3;\ninvariant i : x < 3;\ninvariant i : x > 0;\n",
                 "4:11: invariant 'i' is declared twice"},
        BadInput{"property_atom_without_braces", "semo-ir 1;\nvar x : 0..3;\nproperty p : eventually x > 0;\n",
                 "3:25: expected a state formula in braces '{...}', a temporal operator or '(', found 'x'"},
        BadInput{"property_unclosed_brace", "semo-ir 1;\nvar x : 0..3;\nproperty p : always {x > 0;\n",
                 "3:27: expected '}' to close the state formula, found ';'"},
        BadInput{"property_named_like_an_invariant", "semo-ir 1;\nvar x : 0..3;\ninvariant p : x < 3;\nproperty p : eventually {x > 0};\n",
                 "4:10: property 'p' is declared twice"},
        BadInput{"unknown_kind", "semo-ir 1;\nvar x : 0..3;\nrule r @kind(teleport) : true -> skip;\n",
                 "3:9: unknown rule kind 'teleport' (step, delivery, loss, crash, environment, timer)"},
        BadInput{"empty_range", "semo-ir 1;\nvar x : 3..0;\n", "2:5: empty range: max is below min"},
        BadInput{"assigned_twice", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> x' = 1, x' = 2;\n",
                 "3:26: variable 'x' is assigned twice in one branch"},
        BadInput{"missing_prime", "semo-ir 1;\nvar x : 0..3;\nrule r : true -> x = 1;\n",
                 "3:20: expected ''' after the assigned variable (write x' = ...), found '='"},
        BadInput{"valid_end_twice", "semo-ir 1;\nvalid_end : true;\nvalid_end : false;\n", "3:1: valid_end is given twice"},
        BadInput{"empty_array", "semo-ir 1;\nvar a[0] : 0..3;\n", "2:5: an array needs at least one element"},
        BadInput{"unexpected_character", "semo-ir 1;\nvar x : 0..3;\ninvariant i : x $ 1;\n", "3:17: unexpected character '$'"},
        BadInput{"unterminated_string", "semo-ir 1;\nassume \"no end;\n", "2:8: unterminated string"},
        BadInput{"unknown_item", "semo-ir 1;\nconst x = 1;\n",
                 "2:1: expected 'var', 'rule', 'invariant', 'property', 'valid_end', 'robots' or 'assume', found 'const'"},
        BadInput{"unclosed_parenthesis", "semo-ir 1;\nvar x : 0..3;\ninvariant i : (x > 1;\n",
                 "3:21: expected ')' to close the parenthesis, found ';'"}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return std::string(info.param.what); });

}  // namespace
}  // namespace semo
