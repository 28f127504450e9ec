// --shard K/N of the commands whose work splits over processes (dataset, field).

#include <charconv>

#include "cli.h"
#include "plantarch/Error.h"

namespace plantarch::cli {

std::pair<std::size_t, std::size_t> parseShard(const std::string& text, std::size_t maxShards) {
    const auto bad = [&] {
        return Error("not a shard", {.parameter = "--shard",
                                     .value = text,
                                     .validRange = "K/N, whole numbers with 0 <= K < N <= " +
                                                   std::to_string(maxShards)});
    };
    const auto slash = text.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == text.size()) throw bad();
    std::size_t k = 0, n = 0;
    const char* s = text.data();
    const char* e = s + text.size();
    const auto [kEnd, kErr] = std::from_chars(s, s + slash, k);
    const auto [nEnd, nErr] = std::from_chars(s + slash + 1, e, n);
    if (kErr != std::errc() || kEnd != s + slash || nErr != std::errc() || nEnd != e || n == 0 ||
        n > maxShards || k >= n)
        throw bad();
    return {k, n};
}

}  // namespace plantarch::cli
