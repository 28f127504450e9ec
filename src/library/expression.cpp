// Recursive-descent evaluator of build-step expressions (see expression.h).

#include "library/expression.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

#include "core/value_text.h"
#include "plantarch/Error.h"

namespace plantarch::expr {

namespace {

const std::vector<std::string> kFunctions = {"uniform", "normal", "min",   "max",
                                             "floor",   "ceil",   "round", "abs"};

bool isNameStart(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

class Parser {
public:
    // Evaluating: `variables` and `rng` are used. Checking: only `names` is.
    Parser(std::string_view text, const std::map<std::string, double>* variables, Rng* rng,
           const std::vector<std::string>* names)
        : text_(text), variables_(variables), rng_(rng), names_(names) {}

    double run() {
        skipSpace();
        if (pos_ == text_.size()) fail("empty expression");
        const double v = expression();
        skipSpace();
        if (pos_ != text_.size()) fail("unexpected '" + std::string(1, text_[pos_]) + "'");
        if (evaluating() && !std::isfinite(v)) fail("result is not a finite number");
        return v;
    }

private:
    bool evaluating() const { return names_ == nullptr; }

    [[noreturn]] void fail(const std::string& what, std::string validRange = "",
                           const std::string& hint = "") const {
        throw Error("bad expression: " + what + " at column " + std::to_string(pos_ + 1) + hint,
                    {.value = std::string(text_), .validRange = std::move(validRange)});
    }
    static std::string suggestion(const std::string& near) {
        return near.empty() ? "" : ", did you mean '" + near + "'?";
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
            if (pos_ >= text_.size()) fail(std::string("expected '") + c + "' but the text ended");
            fail(std::string("expected '") + c + "'");
        }
    }

    double expression() {
        double v = term();
        while (true) {
            if (accept('+'))
                v += term();
            else if (accept('-'))
                v -= term();
            else
                return v;
        }
    }

    double term() {
        double v = unary();
        while (true) {
            if (accept('*')) {
                v *= unary();
            } else if (accept('/')) {
                skipSpace();
                const std::size_t at = pos_;
                const double d = unary();
                if (evaluating() && d == 0.0) {
                    pos_ = at;
                    fail("division by zero");
                }
                v = evaluating() ? v / d : 0.0;
            } else {
                return v;
            }
        }
    }

    double unary() {
        if (accept('-')) return -unary();
        if (accept('+')) return unary();
        return primary();
    }

    double primary() {
        skipSpace();
        if (pos_ >= text_.size()) fail("expected a number, name or '(' but the text ended");
        const char c = text_[pos_];
        if (c == '(') {
            ++pos_;
            const double v = expression();
            expect(')');
            return v;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
        if (isNameStart(c)) return name();
        fail("expected a number, name or '(' but found '" + std::string(1, c) + "'");
    }

    double number() {
        double v = 0.0;
        const char* begin = text_.data() + pos_;
        const auto r = std::from_chars(begin, text_.data() + text_.size(), v);
        if (r.ec != std::errc()) fail("malformed number");
        pos_ += std::size_t(r.ptr - begin);
        return v;
    }

    double name() {
        const std::size_t start = pos_;
        while (pos_ < text_.size() && isNameChar(text_[pos_])) ++pos_;
        const std::string id(text_.substr(start, pos_ - start));
        if (accept('(')) return call(id, start);
        if (id == "pi") return std::numbers::pi;
        if (std::find(kFunctions.begin(), kFunctions.end(), id) != kFunctions.end()) {
            pos_ = start;
            fail("function '" + id + "' needs arguments in parentheses");
        }
        if (evaluating()) {
            auto it = variables_->find(id);
            if (it != variables_->end()) return it->second;
        } else if (std::find(names_->begin(), names_->end(), id) != names_->end()) {
            return 0.0;
        }
        std::vector<std::string> known;
        if (evaluating())
            for (const auto& [n, v] : *variables_) known.push_back(n);
        else
            known = *names_;
        known.push_back("pi");
        const std::string near = text::closestMatch(id, known);
        pos_ = start;
        fail("unknown name '" + id + "'", "one of: " + text::joinNames(known), suggestion(near));
    }

    double call(const std::string& fn, std::size_t start) {
        std::vector<double> args;
        skipSpace();
        if (!accept(')')) {
            do args.push_back(expression());
            while (accept(','));
            expect(')');
        }
        auto arity = [&](std::size_t n, const char* names) {
            if (args.size() != n) {
                pos_ = start;
                fail(fn + " takes " + std::to_string(n) + " argument" + (n > 1 ? "s" : "") + " (" +
                     names + "), got " + std::to_string(args.size()));
            }
        };
        if (fn == "uniform") {
            arity(2, "min, max");
            if (!evaluating()) return 0.0;
            if (args[0] > args[1]) {
                pos_ = start;
                fail("uniform: min exceeds max");
            }
            return args[0] + (args[1] - args[0]) * rng_->uniform01d();
        }
        if (fn == "normal") {
            arity(2, "mean, stddev");
            if (!evaluating()) return 0.0;
            if (args[1] < 0.0) {
                pos_ = start;
                fail("normal: negative stddev");
            }
            return args[0] + args[1] * rng_->normal01();
        }
        if (fn == "min" || fn == "max") {
            if (args.empty()) {
                pos_ = start;
                fail(fn + " needs at least one argument");
            }
            return fn == "min" ? *std::min_element(args.begin(), args.end())
                               : *std::max_element(args.begin(), args.end());
        }
        if (fn == "floor" || fn == "ceil" || fn == "round" || fn == "abs") {
            arity(1, "x");
            if (fn == "floor") return std::floor(args[0]);
            if (fn == "ceil") return std::ceil(args[0]);
            if (fn == "round") return std::round(args[0]);
            return std::abs(args[0]);
        }
        const std::string near = text::closestMatch(fn, kFunctions);
        pos_ = start;
        fail("unknown function '" + fn + "'", "one of: " + text::joinNames(kFunctions),
             suggestion(near));
    }

    std::string_view text_;
    std::size_t pos_ = 0;
    const std::map<std::string, double>* variables_;
    Rng* rng_;
    const std::vector<std::string>* names_;
};

}  // namespace

double evaluate(std::string_view text, const std::map<std::string, double>& variables, Rng& rng) {
    return Parser(text, &variables, &rng, nullptr).run();
}

void check(std::string_view text, const std::vector<std::string>& names) {
    Parser(text, nullptr, nullptr, &names).run();
}

const std::vector<std::string>& reservedNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n = kFunctions;
        n.push_back("pi");
        return n;
    }();
    return names;
}

}  // namespace plantarch::expr
