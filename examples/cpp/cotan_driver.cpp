// A cotan Laplacian in C++, checked by ddg-oracle through the executable protocol
// (docs/protocol.md; the JSON reading and writing is in ddg_protocol.hpp).
//
//   g++ -O2 -std=c++17 -o cotan_driver cotan_driver.cpp      (or: bash build.sh)
//   ddg-oracle check --impl 'exec:./cotan_driver'
//   ddg-oracle check --impl 'exec:./cotan_driver --bug=boundary'   # caught, 1 triangle
//
// A template for your own driver: replace cotan_laplacian() with a call into your code.
#include <cmath>
#include <map>

#include "ddg_protocol.hpp"

// The cotan Laplacian (L f)(i) = sum_j w_ij (f(i) - f(j)), w = 1/2 (cot a + cot b), as
// triplets.  bug_boundary: a boundary edge gets cot a instead of 1/2 cot a.
static std::string cotan_laplacian(const ddg::Mesh& mesh, bool bug_boundary, bool bug_sign) {
    std::map<std::pair<long, long>, double> w;
    std::map<std::pair<long, long>, int> faces_of_edge;
    for (const auto& f : mesh.F) {
        for (int c = 0; c < 3; ++c) {
            long k = f[c], i = f[(c + 1) % 3], j = f[(c + 2) % 3];
            std::array<double, 3> u, v;
            for (int d = 0; d < 3; ++d) {
                u[d] = mesh.V[i][d] - mesh.V[k][d];
                v[d] = mesh.V[j][d] - mesh.V[k][d];
            }
            double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2],
                   cz = u[0] * v[1] - u[1] * v[0];
            double cot = dot / std::sqrt(cx * cx + cy * cy + cz * cz);
            auto e = std::make_pair(std::min(i, j), std::max(i, j));
            w[e] += cot / 2;
            faces_of_edge[e] += 1;
        }
    }
    ddg::Triplets L;
    L.n = mesh.V.size();
    for (auto& [e, x] : w) {
        if (bug_boundary && faces_of_edge[e] == 1) x *= 2;
        L.add_edge_weight(e.first, e.second, bug_sign ? -x : x);
    }
    return L.json();
}

int main(int argc, char** argv) {
    bool bug_boundary = false, bug_sign = false;
    for (int a = 1; a < argc; ++a) {
        std::string arg = argv[a];
        if (arg == "--bug=boundary") bug_boundary = true;
        else if (arg == "--bug=sign") bug_sign = true;
        else { std::cerr << "unknown argument " << arg << "\n"; return 2; }
    }
    ddg::Driver driver{bug_boundary ? "cpp-cotan-boundary-bug"
                       : bug_sign   ? "cpp-cotan-sign-bug" : "cpp-cotan",
                       {"cotan_laplacian"}};
    return driver.serve([&](const std::string& method, const ddg::Mesh& mesh) {
        if (method != "cotan_laplacian") throw std::runtime_error("not implemented");
        return cotan_laplacian(mesh, bug_boundary, bug_sign);
    });
}
