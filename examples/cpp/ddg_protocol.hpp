// The executable protocol (docs/protocol.md) for C++ drivers: one JSON request per line
// on stdin, one JSON answer per line on stdout.  Header-only, C++17, no dependency.
//
//   int main(int argc, char** argv) {
//       ddg::Driver d{"my-lib", {"area", "cotan_laplacian"}};
//       return d.serve([](const std::string& method, const ddg::Mesh& mesh) {
//           if (method == "area") return ddg::num(my_area(mesh.V, mesh.F));
//           throw ddg::OutsideDomain("not implemented");
//       });
//   }
//
// The handler returns the answer's `value` as JSON text; it throws ddg::OutsideDomain
// for "no value on this input in the reference's conventions" and any other
// std::exception for a failure (both are answered as error objects, the driver goes on).
// Numbers are read with strtod and written with %.17g, so float64 round-trips exactly.
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace ddg {

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

// What ddg-oracle sends: objects, arrays, numbers, strings, true/false/null.
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

// NaN and infinities as Python's json module reads them (not strict JSON: a wrong value
// is then reported as a wrong value, not as garbage)
inline std::string num(double x) {
    if (std::isnan(x)) return "NaN";
    if (std::isinf(x)) return x > 0 ? "Infinity" : "-Infinity";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

inline std::string quote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (c == '\n') { out += "\\n"; continue; }
        out += c;
    }
    return out + "\"";
}

template <class T, class F>
std::string list(const std::vector<T>& xs, F item) {
    std::string out = "[";
    for (size_t i = 0; i < xs.size(); ++i) out += (i ? "," : "") + item(xs[i]);
    return out + "]";
}

inline std::string numbers(const std::vector<double>& xs) {
    return list(xs, [](double x) { return num(x); });
}

// A sparse n x n matrix as the protocol's {"shape", "rows", "cols", "values"} (duplicates summed).
struct Triplets {
    size_t n = 0;
    std::vector<long> rows, cols;
    std::vector<double> values;
    void add(long r, long c, double x) { rows.push_back(r); cols.push_back(c); values.push_back(x); }
    // the Laplacian convention of the protocol: (L f)(i) = sum_j w_ij (f(i) - f(j))
    void add_edge_weight(long i, long j, double w) {
        add(i, j, -w); add(j, i, -w); add(i, i, w); add(j, j, w);
    }
    std::string json() const {
        auto ints = [](const std::vector<long>& xs) {
            return list(xs, [](long x) { return std::to_string(x); });
        };
        return "{\"shape\":[" + std::to_string(n) + "," + std::to_string(n) + "],\"rows\":" +
               ints(rows) + ",\"cols\":" + ints(cols) + ",\"values\":" + numbers(values) + "}";
    }
};

struct Mesh {
    std::vector<std::array<double, 3>> V;
    std::vector<std::array<long, 3>> F;
    // solve_dirichlet only: the boundary set and its values
    std::vector<long> boundary;
    std::vector<double> values;
};

struct OutsideDomain : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Driver {
    std::string name;
    std::vector<std::string> methods;
    // the hello answer's "conventions" object, as JSON text (docs/protocol.md)
    std::string conventions = "{}";

    using Handler = std::function<std::string(const std::string&, const Mesh&)>;

    int serve(const Handler& handle) const {
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
            const std::string method = request["method"].text;
            if (method == "hello") {
                std::cout << "{\"name\":" << quote(name) << ",\"methods\":"
                          << list(methods, quote) << ",\"machine_epsilon\":"
                          << num(2.220446049250313e-16) << ",\"conventions\":" << conventions
                          << "}" << std::endl;
                continue;
            }
            const long id = long(request["id"].number);
            Mesh mesh;
            for (const auto& p : request["V"].items)
                mesh.V.push_back({p.items[0].number, p.items[1].number, p.items[2].number});
            for (const auto& f : request["F"].items)
                mesh.F.push_back({long(f.items[0].number), long(f.items[1].number),
                                  long(f.items[2].number)});
            for (const auto& b : request["boundary"].items) mesh.boundary.push_back(long(b.number));
            for (const auto& x : request["values"].items) mesh.values.push_back(x.number);
            std::string answer;
            try {
                answer = "\"value\":" + handle(method, mesh);
            } catch (const OutsideDomain& e) {
                answer = "\"error\":{\"kind\":\"outside_domain\",\"message\":" + quote(e.what()) + "}";
            } catch (const std::exception& e) {
                answer = "\"error\":{\"kind\":\"failed\",\"message\":" + quote(e.what()) + "}";
            }
            std::cout << "{\"id\":" << id << "," << answer << "}" << std::endl;
        }
        return 0;
    }
};

}  // namespace ddg
