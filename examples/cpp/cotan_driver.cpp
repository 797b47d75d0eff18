// A cotan Laplacian in C++, checked by ddg-oracle through the executable protocol
// (docs/protocol.md): one JSON request per line on stdin, one JSON answer per line on stdout.
//
//   g++ -O2 -std=c++17 -o cotan_driver cotan_driver.cpp      (or: cmake -S . -B build)
//   ddg-oracle check --impl 'exec:./cotan_driver'
//   ddg-oracle check --impl 'exec:./cotan_driver --bug=boundary'   # caught, 1 triangle
//
// A template for your own driver: replace cotan_laplacian() with a call into your code.
// The JSON reader below handles what ddg-oracle sends (objects, arrays, numbers, strings);
// numbers are read with strtod and written with %.17g, so floats round-trip exactly.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

struct Json {
    enum Kind { Null, Bool, Number, String, Array, Object } kind = Null;
    double number = 0;
    bool boolean = false;
    std::string text;
    std::vector<Json> items;
    std::map<std::string, Json> fields;
    const Json& operator[](const std::string& k) const {
        static const Json none;
        auto it = fields.find(k);
        return it == fields.end() ? none : it->second;
    }
};

struct Reader {
    const char* p;
    void space() { while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') ++p; }
    Json value() {
        space();
        Json j;
        if (*p == '{') {
            j.kind = Json::Object; ++p; space();
            if (*p == '}') { ++p; return j; }
            for (;;) {
                std::string key = value().text; space();
                if (*p++ != ':') throw std::runtime_error("expected ':'");
                j.fields[key] = value(); space();
                if (*p == ',') { ++p; continue; }
                if (*p++ != '}') throw std::runtime_error("expected '}'");
                return j;
            }
        }
        if (*p == '[') {
            j.kind = Json::Array; ++p; space();
            if (*p == ']') { ++p; return j; }
            for (;;) {
                j.items.push_back(value()); space();
                if (*p == ',') { ++p; continue; }
                if (*p++ != ']') throw std::runtime_error("expected ']'");
                return j;
            }
        }
        if (*p == '"') {
            j.kind = Json::String; ++p;
            while (*p && *p != '"') { if (*p == '\\') ++p; j.text += *p++; }
            if (*p++ != '"') throw std::runtime_error("unterminated string");
            return j;
        }
        if (std::string(p, 4) == "true") { p += 4; j.kind = Json::Bool; j.boolean = true; return j; }
        if (std::string(p, 5) == "false") { p += 5; j.kind = Json::Bool; return j; }
        if (std::string(p, 4) == "null") { p += 4; return j; }
        char* end = nullptr;
        j.kind = Json::Number;
        j.number = std::strtod(p, &end);
        if (end == p) throw std::runtime_error("bad JSON value");
        p = end;
        return j;
    }
};

static std::string num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

using Vec = std::array<double, 3>;

// The cotan Laplacian (L f)(i) = sum_j w_ij (f(i) - f(j)), w = 1/2 (cot a + cot b), as
// triplets.  bug_boundary: a boundary edge gets cot a instead of 1/2 cot a.
static std::string cotan_laplacian(const std::vector<Vec>& V, const std::vector<std::array<long, 3>>& F,
                                   bool bug_boundary, bool bug_sign) {
    std::map<std::pair<long, long>, double> w;
    std::map<std::pair<long, long>, int> faces_of_edge;
    for (const auto& f : F) {
        for (int c = 0; c < 3; ++c) {
            long k = f[c], i = f[(c + 1) % 3], j = f[(c + 2) % 3];
            Vec u, v;
            for (int d = 0; d < 3; ++d) { u[d] = V[i][d] - V[k][d]; v[d] = V[j][d] - V[k][d]; }
            double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2],
                   cz = u[0] * v[1] - u[1] * v[0];
            double cot = dot / std::sqrt(cx * cx + cy * cy + cz * cz);
            auto e = std::make_pair(std::min(i, j), std::max(i, j));
            w[e] += cot / 2;
            faces_of_edge[e] += 1;
        }
    }
    std::vector<double> diag(V.size(), 0.0);
    std::ostringstream rows, cols, vals;
    bool first = true;
    auto put = [&](long r, long c, double x) {
        rows << (first ? "" : ",") << r;
        cols << (first ? "" : ",") << c;
        vals << (first ? "" : ",") << num(bug_sign ? -x : x);
        first = false;
    };
    for (auto& [e, x] : w) {
        if (bug_boundary && faces_of_edge[e] == 1) x *= 2;
        put(e.first, e.second, -x);
        put(e.second, e.first, -x);
        diag[e.first] += x;
        diag[e.second] += x;
    }
    for (size_t i = 0; i < V.size(); ++i) put(long(i), long(i), diag[i]);
    return "{\"shape\":[" + std::to_string(V.size()) + "," + std::to_string(V.size()) +
           "],\"rows\":[" + rows.str() + "],\"cols\":[" + cols.str() + "],\"values\":[" +
           vals.str() + "]}";
}

int main(int argc, char** argv) {
    bool bug_boundary = false, bug_sign = false;
    for (int a = 1; a < argc; ++a) {
        std::string arg = argv[a];
        if (arg == "--bug=boundary") bug_boundary = true;
        else if (arg == "--bug=sign") bug_sign = true;
        else { std::cerr << "unknown argument " << arg << "\n"; return 2; }
    }
    std::string line;
    while (std::getline(std::cin, line)) {
        if (line.empty()) continue;
        Json request;
        try {
            Reader r{line.c_str()};
            request = r.value();
        } catch (const std::exception& e) {
            std::cerr << "cannot parse request: " << e.what() << "\n";
            return 1;
        }
        std::string method = request["method"].text;
        if (method == "hello") {
            std::string name = bug_boundary ? "cpp-cotan-boundary-bug"
                             : bug_sign ? "cpp-cotan-sign-bug" : "cpp-cotan";
            std::cout << "{\"name\":\"" << name << "\",\"methods\":[\"cotan_laplacian\"],"
                      << "\"machine_epsilon\":" << num(2.220446049250313e-16) << "}" << std::endl;
            continue;
        }
        long id = long(request["id"].number);
        if (method != "cotan_laplacian") {
            std::cout << "{\"id\":" << id << ",\"error\":{\"kind\":\"failed\",\"message\":"
                      << "\"not implemented\"}}" << std::endl;
            continue;
        }
        std::vector<Vec> V;
        for (const auto& p : request["V"].items) V.push_back({p.items[0].number, p.items[1].number,
                                                               p.items[2].number});
        std::vector<std::array<long, 3>> F;
        for (const auto& f : request["F"].items)
            F.push_back({long(f.items[0].number), long(f.items[1].number), long(f.items[2].number)});
        std::cout << "{\"id\":" << id << ",\"value\":"
                  << cotan_laplacian(V, F, bug_boundary, bug_sign) << "}" << std::endl;
    }
    return 0;
}
