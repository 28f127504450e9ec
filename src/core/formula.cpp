// Formulas (plantarch/Formula.h): a recursive-descent parser that compiles the text into a
// postfix program once, and an evaluator of that program in double or float precision.

#include "plantarch/Formula.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch {

namespace {

enum class Fn { Uniform, Normal, Min, Max, Floor, Ceil, Round, Abs };

struct FunctionInfo {
    const char* name;
    Fn fn;
    int arity;  ///< -1: one or more
    const char* argumentNames;
    bool random;
};

constexpr FunctionInfo kFunctions[] = {
    {"uniform", Fn::Uniform, 2, "min, max", true},
    {"normal", Fn::Normal, 2, "mean, stddev", true},
    {"min", Fn::Min, -1, "", false},
    {"max", Fn::Max, -1, "", false},
    {"floor", Fn::Floor, 1, "x", false},
    {"ceil", Fn::Ceil, 1, "x", false},
    {"round", Fn::Round, 1, "x", false},
    {"abs", Fn::Abs, 1, "x", false},
};

std::vector<std::string> functionNames(bool allowRandom) {
    std::vector<std::string> names;
    for (const FunctionInfo& f : kFunctions)
        if (allowRandom || !f.random) names.emplace_back(f.name);
    return names;
}

const FunctionInfo* findFunction(const std::string& name) {
    for (const FunctionInfo& f : kFunctions)
        if (name == f.name) return &f;
    return nullptr;
}

bool isNameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

[[noreturn]] void fail(std::string_view text, std::size_t column, const std::string& what,
                       std::string validRange = "", const std::string& hint = "") {
    throw Error("bad expression: " + what + " at column " + std::to_string(column) + hint,
                {.value = std::string(text), .validRange = std::move(validRange)});
}

std::string suggestion(const std::string& near) {
    return near.empty() ? "" : ", did you mean '" + near + "'?";
}

}  // namespace

struct Formula::Program {
    enum class Kind { Number, Variable, Negate, Add, Subtract, Multiply, Divide, Call };
    struct Op {
        Kind kind;
        double number = 0.0;    ///< Number: the literal as a double
        float numberF = 0.0f;   ///< Number: the literal as the nearest float
        std::size_t index = 0;  ///< Variable: its index; Call: argument count
        Fn fn = Fn::Min;
        std::size_t column = 0;  ///< where an evaluation error is reported (1-based)
    };
    std::vector<std::string> variables;
    std::vector<Op> ops;
    std::size_t endColumn = 1;
    std::size_t depth = 1;  ///< the deepest the value stack gets
    bool random = false;    ///< has uniform() or normal()
};

namespace {

using Program = Formula::Program;
using Op = Program::Op;
using Kind = Program::Kind;

class Parser {
public:
    Parser(std::string_view text, Program& out, bool allowRandom)
        : text_(text), out_(out), allowRandom_(allowRandom) {}

    void run() {
        skipSpace();
        if (pos_ == text_.size()) failHere("empty expression");
        expression();
        skipSpace();
        if (pos_ != text_.size()) failHere("unexpected '" + std::string(1, text_[pos_]) + "'");
        out_.endColumn = text_.size() + 1;
    }

private:
    [[noreturn]] void failHere(const std::string& what, std::string validRange = "",
                               const std::string& hint = "") const {
        fail(text_, pos_ + 1, what, std::move(validRange), hint);
    }

    void emit(Op op, int stackChange) {
        out_.ops.push_back(op);
        stack_ += stackChange;
        out_.depth = std::max(out_.depth, std::size_t(std::max(stack_, 1)));
    }

    void skipSpace() {
        while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    }
    bool accept(char c) {
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == c) {
            ++pos_;
            return true;
        }
        return false;
    }
    void expect(char c) {
        if (!accept(c)) {
            if (pos_ >= text_.size())
                failHere(std::string("expected '") + c + "' but the text ended");
            failHere(std::string("expected '") + c + "'");
        }
    }

    void expression() {
        term();
        while (true) {
            if (accept('+')) {
                term();
                emit({.kind = Kind::Add}, -1);
            } else if (accept('-')) {
                term();
                emit({.kind = Kind::Subtract}, -1);
            } else {
                return;
            }
        }
    }

    void term() {
        unary();
        while (true) {
            if (accept('*')) {
                unary();
                emit({.kind = Kind::Multiply}, -1);
            } else if (accept('/')) {
                skipSpace();
                const std::size_t at = pos_ + 1;
                unary();
                emit({.kind = Kind::Divide, .column = at}, -1);
            } else {
                return;
            }
        }
    }

    // Every nesting (a parenthesis, a call's argument, a sign) passes through unary(), so the
    // depth counted here bounds the parser's recursion: a hostile text cannot exhaust the stack.
    struct Nest {
        Parser& p;
        explicit Nest(Parser& parser) : p(parser) {
            if (++p.nesting_ > kMaxNesting)
                p.failHere("nested deeper than " + std::to_string(kMaxNesting) + " levels",
                           "at most " + std::to_string(kMaxNesting) +
                               " nested parentheses, calls and signs");
        }
        ~Nest() { --p.nesting_; }
        Nest(const Nest&) = delete;
        Nest& operator=(const Nest&) = delete;
    };

    void unary() {
        const Nest nest(*this);
        if (accept('-')) {
            unary();
            emit({.kind = Kind::Negate}, 0);
            return;
        }
        if (accept('+')) return unary();
        primary();
    }

    void primary() {
        skipSpace();
        if (pos_ >= text_.size()) failHere("expected a number, name or '(' but the text ended");
        const char c = text_[pos_];
        if (c == '(') {
            ++pos_;
            expression();
            expect(')');
            return;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
        if (isNameStart(c)) return name();
        failHere("expected a number, name or '(' but found '" + std::string(1, c) + "'");
    }

    void number() {
        Op op{.kind = Kind::Number};
        const char* begin = text_.data() + pos_;
        const char* end = text_.data() + text_.size();
        const auto r = std::from_chars(begin, end, op.number);
        if (r.ec != std::errc()) failHere("malformed number");
        // The same digits rounded once to float; beyond float's range, infinity (an error when
        // a float evaluation reaches the result).
        if (std::from_chars(begin, r.ptr, op.numberF).ec != std::errc())
            op.numberF = float(op.number);
        pos_ += std::size_t(r.ptr - begin);
        emit(op, 1);
    }

    void name() {
        const std::size_t start = pos_;
        while (pos_ < text_.size() && isNameChar(text_[pos_])) ++pos_;
        const std::string id(text_.substr(start, pos_ - start));
        if (accept('(')) return call(id, start);
        if (id == "pi") {
            emit({.kind = Kind::Number,
                  .number = std::numbers::pi,
                  .numberF = std::numbers::pi_v<float>},
                 1);
            return;
        }
        if (findFunction(id)) {
            pos_ = start;
            failHere("function '" + id + "' needs arguments in parentheses");
        }
        const auto& vars = out_.variables;
        const auto it = std::find(vars.begin(), vars.end(), id);
        if (it != vars.end()) {
            emit({.kind = Kind::Variable, .index = std::size_t(it - vars.begin())}, 1);
            return;
        }
        std::vector<std::string> known = vars;
        known.push_back("pi");
        const std::string near = text::closestMatch(id, known);
        pos_ = start;
        failHere("unknown name '" + id + "'", "one of: " + text::joinNames(known),
                 suggestion(near));
    }

    void call(const std::string& id, std::size_t start) {
        std::size_t count = 0;
        skipSpace();
        if (!accept(')')) {
            do {
                expression();
                ++count;
            } while (accept(','));
            expect(')');
        }
        const FunctionInfo* f = findFunction(id);
        if (!f || (f->random && !allowRandom_)) {
            const std::vector<std::string> names = functionNames(allowRandom_);
            const std::string near = text::closestMatch(id, names);
            pos_ = start;
            if (f)
                failHere("random function '" + id + "' is not allowed here",
                         "one of: " + text::joinNames(names));
            failHere("unknown function '" + id + "'", "one of: " + text::joinNames(names),
                     suggestion(near));
        }
        if (f->arity < 0 && count == 0) {
            pos_ = start;
            failHere(id + " needs at least one argument");
        }
        if (f->arity > 0 && count != std::size_t(f->arity)) {
            pos_ = start;
            failHere(id + " takes " + std::to_string(f->arity) + " argument" +
                     (f->arity > 1 ? "s" : "") + " (" + f->argumentNames + "), got " +
                     std::to_string(count));
        }
        out_.random = out_.random || f->random;
        emit({.kind = Kind::Call, .index = count, .fn = f->fn, .column = start + 1},
             1 - int(count));
    }

    std::string_view text_;
    Program& out_;
    bool allowRandom_;
    static constexpr int kMaxNesting = 200;
    std::size_t pos_ = 0;
    int stack_ = 0;
    int nesting_ = 0;
};

template <class T>
T run(const Program& p, std::string_view text, const T* values, Rng* rng) {
    // A small fixed stack covers every formula a person writes; deeper ones use the heap.
    std::array<T, 32> small{};
    std::vector<T> large;
    T* stack = small.data();
    if (p.depth > 32) {
        large.resize(p.depth);
        stack = large.data();
    }
    std::size_t n = 0;
    for (const Op& op : p.ops) {
        switch (op.kind) {
            case Kind::Number:
                if constexpr (std::is_same_v<T, float>)
                    stack[n++] = op.numberF;
                else
                    stack[n++] = op.number;
                break;
            case Kind::Variable:
                stack[n++] = values[op.index];
                break;
            case Kind::Negate:
                stack[n - 1] = -stack[n - 1];
                break;
            case Kind::Add:
                --n;
                stack[n - 1] = stack[n - 1] + stack[n];
                break;
            case Kind::Subtract:
                --n;
                stack[n - 1] = stack[n - 1] - stack[n];
                break;
            case Kind::Multiply:
                --n;
                stack[n - 1] = stack[n - 1] * stack[n];
                break;
            case Kind::Divide:
                --n;
                if (stack[n] == T(0)) fail(text, op.column, "division by zero");
                stack[n - 1] = stack[n - 1] / stack[n];
                break;
            case Kind::Call: {
                const std::size_t argc = op.index;
                T* args = stack + (n - argc);
                T v = args[0];
                switch (op.fn) {
                    case Fn::Uniform:
                        if (args[0] > args[1]) fail(text, op.column, "uniform: min exceeds max");
                        if constexpr (std::is_same_v<T, double>)
                            v = args[0] + (args[1] - args[0]) * rng->uniform01d();
                        break;
                    case Fn::Normal:
                        if (args[1] < T(0)) fail(text, op.column, "normal: negative stddev");
                        if constexpr (std::is_same_v<T, double>)
                            v = args[0] + args[1] * rng->normal01();
                        break;
                    case Fn::Min:
                        v = *std::min_element(args, args + argc);
                        break;
                    case Fn::Max:
                        v = *std::max_element(args, args + argc);
                        break;
                    case Fn::Floor:
                        v = std::floor(v);
                        break;
                    case Fn::Ceil:
                        v = std::ceil(v);
                        break;
                    case Fn::Round:
                        v = std::round(v);
                        break;
                    case Fn::Abs:
                        v = std::abs(v);
                        break;
                }
                n -= argc;
                stack[n++] = v;
                break;
            }
        }
    }
    if (!std::isfinite(stack[0])) fail(text, p.endColumn, "result is not a finite number");
    return stack[0];
}

}  // namespace

Formula::Formula(std::string_view text, std::vector<std::string> variables, bool allowRandom)
    : text_(text) {
    auto program = std::make_shared<Program>();
    program->variables = std::move(variables);
    Parser(text_, *program, allowRandom).run();
    program_ = std::move(program);
}

const std::vector<std::string>& Formula::variables() const {
    static const std::vector<std::string> none;
    return program_ ? program_->variables : none;
}

void Formula::checkCall(std::size_t valueCount) const {
    if (!program_) throw Error("an empty formula cannot be evaluated");
    if (valueCount != program_->variables.size())
        throw Error("a formula was given " + std::to_string(valueCount) + " values for " +
                        std::to_string(program_->variables.size()) + " variables",
                    {.value = text_});
}

double Formula::evaluate(std::span<const double> values, Rng* rng) const {
    checkCall(values.size());
    if (program_->random && !rng)
        throw Error("a formula with random draws needs a random stream", {.value = text_});
    return run<double>(*program_, text_, values.data(), rng);
}

float Formula::evaluateFloat(std::span<const float> values) const {
    checkCall(values.size());
    if (program_->random)
        throw Error("random draws are evaluated in double precision only", {.value = text_});
    return run<float>(*program_, text_, values.data(), nullptr);
}

const std::vector<std::string>& Formula::reservedNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n = functionNames(true);
        n.push_back("pi");
        return n;
    }();
    return names;
}

}  // namespace plantarch
