// Attraction points from a CSV file of x,y,z lines.

#include <cctype>
#include <cmath>
#include <sstream>

#include "core/input_file.h"
#include "plantarch/Collision.h"
#include "plantarch/Error.h"

namespace plantarch {

std::vector<vec3> readAttractionPointsCSV(const std::string& path, const std::string& parameter) {
    std::istringstream in(io::readWholeFile(path, io::kAttractionFile));
    std::vector<vec3> points;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::stringstream ss(line);
        std::vector<double> v;
        bool ok = true, anyNumber = false;
        for (std::string part; std::getline(ss, part, ',');) {
            std::size_t used = 0;
            try {
                v.push_back(std::stod(part, &used));
                anyNumber = true;
            } catch (const std::out_of_range&) {  // 1e999: a number, but not a finite one
                ok = false;
                anyNumber = true;
                break;
            } catch (const std::exception&) {
                ok = false;
                continue;
            }
            while (used < part.size() && std::isspace(static_cast<unsigned char>(part[used])))
                ++used;
            if (used != part.size() || !std::isfinite(v.back())) ok = false;
        }
        if (!anyNumber && number == 1) continue;  // a header such as "x,y,z"
        if (!ok || v.size() != 3)
            throw Error("expected three finite numbers x,y,z (m)",
                        {.file = path,
                         .line = number,
                         .parameter = parameter,
                         .value = line.substr(0, 60),
                         .validRange = "e.g. 0.5,0,1.2"});
        points.push_back(vec3(float(v[0]), float(v[1]), float(v[2])));
    }
    if (points.empty())
        throw Error("attraction point file holds no points",
                    {.file = path, .parameter = parameter, .validRange = "lines of x,y,z"});
    return points;
}

}  // namespace plantarch
