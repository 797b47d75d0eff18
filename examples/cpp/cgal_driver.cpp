// CGAL 5.5 (Debian libcgal-dev, header-only) checked by ddg-oracle through the
// executable protocol (docs/protocol.md).  Built by build.sh when CMake finds CGAL.
//
//   ddg-oracle check --impl 'exec:examples/cpp/build/cgal_driver'
//   ddg-oracle check --impl 'exec:examples/cpp/build/cgal_driver --weights=library'
//
// What is called, on a CGAL::Surface_mesh over Simple_cartesian<double>:
//   cotan_laplacian               Weights::Edge_cotangent_weight (the weight of
//                                 PMP::smooth_shape's curvature flow) on the edge's
//                                 non-border halfedge, halved: CGAL's weight is
//                                 cot a + cot b inside and cot a at the boundary, 2x
//                                 the notes' (--weights=library: as CGAL gives it)
//   vertex_areas_voronoi          Weights::mixed_voronoi_area(p, q, r) per corner q
//   vertex_areas_barycentric      Weights::barycentric_area(p, q, r) per corner q
//   area                          Polygon_mesh_processing::area
//   area_gradient                 L V with the same (halved) Edge_cotangent_weight
//   solve_dirichlet               L_II u_I = -L_IB c with the same weights, Eigen's
//                                 SparseLU (the solver CGAL's Eigen traits offer)
//   intrinsic_delaunay_laplacian  Heat_method_3's Intrinsic_Delaunay_triangulation_3
//                                 (the heat method's iDT mode): cotan weights read off
//                                 its per-face layouts (hcmap), 1/2 (cot a + cot b)
//   intrinsic_delaunay_triangulation  the same triangulation's faces (input vertex
//                                 indices) and squared edge lengths
// The notes' weight 1/2 (cot a + cot b) is CGAL's Weights::cotangent_weight / 4.
#include <CGAL/Heat_method_3/internal/Intrinsic_Delaunay_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Weights/barycentric_region_weights.h>
#include <CGAL/Weights/cotangent_weights.h>
#include <CGAL/Weights/mixed_voronoi_region_weights.h>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include "ddg_protocol.hpp"

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace PMP = CGAL::Polygon_mesh_processing;

static SurfaceMesh surface_mesh(const ddg::Mesh& mesh) {
    SurfaceMesh sm;
    for (const auto& p : mesh.V) sm.add_vertex(Point(p[0], p[1], p[2]));
    for (size_t f = 0; f < mesh.F.size(); ++f) {
        const auto& t = mesh.F[f];
        for (long i : t)
            if (i < 0 || size_t(i) >= mesh.V.size())
                throw std::runtime_error("face " + std::to_string(f) + ": index out of range");
        if (sm.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2])) ==
            SurfaceMesh::null_face())
            // Surface_mesh holds oriented 2-manifolds only
            throw ddg::OutsideDomain("Surface_mesh::add_face refused face " + std::to_string(f) +
                                     " (non-orientable or non-manifold)");
    }
    return sm;
}

static ddg::Triplets cotan_triplets(const SurfaceMesh& sm, double factor) {
    CGAL::Weights::Edge_cotangent_weight<SurfaceMesh> weight(sm, sm.points());
    ddg::Triplets L;
    L.n = sm.number_of_vertices();
    for (auto e : sm.edges()) {
        auto h = sm.halfedge(e);
        // as curvature_flow_impl.h does: the halfedge that has a face
        if (sm.is_border(h)) h = sm.opposite(h);
        L.add_edge_weight(sm.source(h).idx(), sm.target(h).idx(), factor * weight(h));
    }
    return L;
}

static std::string cotan_laplacian(const SurfaceMesh& sm, double factor) {
    return cotan_triplets(sm, factor).json();
}

// grad_v A = (L V)(v) (T3.9), L with the notes' weights
static std::string area_gradient(const SurfaceMesh& sm) {
    ddg::Triplets L = cotan_triplets(sm, 0.5);
    std::vector<std::array<double, 3>> G(L.n, {0.0, 0.0, 0.0});
    for (size_t k = 0; k < L.values.size(); ++k) {
        const Point& p = sm.point(VertexIndex(L.cols[k]));
        for (int d = 0; d < 3; ++d) G[L.rows[k]][d] += L.values[k] * p[d];
    }
    return ddg::list(G, [](const std::array<double, 3>& g) {
        return "[" + ddg::num(g[0]) + "," + ddg::num(g[1]) + "," + ddg::num(g[2]) + "]";
    });
}

// the Dirichlet problem (C3.4): u = c on the boundary set, (L u)(i) = 0 elsewhere
static std::string solve_dirichlet(const SurfaceMesh& sm, const ddg::Mesh& mesh) {
    const long n = long(sm.number_of_vertices());
    if (mesh.boundary.size() != mesh.values.size())
        throw std::runtime_error("boundary and values differ in length");
    std::vector<double> u(n, 0.0);
    std::vector<long> slot(n, -1);          // index among the unknowns, -1 on the boundary
    std::vector<bool> fixed(n, false);
    for (size_t k = 0; k < mesh.boundary.size(); ++k) {
        const long b = mesh.boundary[k];
        if (b < 0 || b >= n) throw std::runtime_error("boundary vertex out of range");
        fixed[b] = true;
        u[b] = mesh.values[k];
    }
    long m = 0;
    for (long v = 0; v < n; ++v)
        if (!fixed[v]) slot[v] = m++;
    if (m == 0) return ddg::numbers(u);
    ddg::Triplets L = cotan_triplets(sm, 0.5);
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m);
    for (size_t k = 0; k < L.values.size(); ++k) {
        const long i = L.rows[k], j = L.cols[k];
        if (slot[i] < 0) continue;
        if (slot[j] >= 0) entries.emplace_back(slot[i], slot[j], L.values[k]);
        else rhs[slot[i]] -= L.values[k] * u[j];
    }
    Eigen::SparseMatrix<double> A(m, m);
    A.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(A);
    if (lu.info() != Eigen::Success)
        throw std::runtime_error("SparseLU: the Dirichlet system is singular");
    Eigen::VectorXd x = lu.solve(rhs);
    for (long v = 0; v < n; ++v)
        if (slot[v] >= 0) u[v] = x[slot[v]];
    return ddg::numbers(u);
}

template <class Area>
static std::string corner_areas(const SurfaceMesh& sm, Area area) {
    std::vector<double> A(sm.number_of_vertices(), 0.0);
    for (auto f : sm.faces())
        for (auto h : CGAL::halfedges_around_face(sm.halfedge(f), sm)) {
            // the corner at target(h), between source(h) and target(next(h))
            const Point& p = sm.point(sm.source(h));
            const Point& q = sm.point(sm.target(h));
            const Point& r = sm.point(sm.target(sm.next(h)));
            A[sm.target(h).idx()] += area(p, q, r);
        }
    return ddg::numbers(A);
}

using IDT = CGAL::Heat_method_3::Intrinsic_Delaunay_triangulation_3<SurfaceMesh, Kernel>;

// The iDT's faces as (input vertex index, 2D position) per corner, from its layouts.
struct IntrinsicFace {
    std::array<long, 3> v;
    std::array<std::pair<double, double>, 3> p;
};

static std::vector<IntrinsicFace> intrinsic_faces(const SurfaceMesh& sm) {
    IDT idt(sm);
    const SurfaceMesh& tm = idt.triangle_mesh();
    std::vector<IntrinsicFace> out;
    for (auto f : tm.faces()) {
        IntrinsicFace face;
        int c = 0;
        // hcmap()[h] is the position of target(h) in the layout of face(h)
        for (auto h : CGAL::halfedges_around_face(tm.halfedge(f), tm)) {
            face.v[c] = idt.v2v.at(tm.target(h)).idx();
            face.p[c] = get(idt.hcmap(), h);
            ++c;
        }
        out.push_back(face);
    }
    return out;
}

static double cot_at(const IntrinsicFace& f, int c) {
    auto [x0, y0] = f.p[c];
    auto [x1, y1] = f.p[(c + 1) % 3];
    auto [x2, y2] = f.p[(c + 2) % 3];
    double ux = x1 - x0, uy = y1 - y0, vx = x2 - x0, vy = y2 - y0;
    return (ux * vx + uy * vy) / std::abs(ux * vy - uy * vx);
}

static std::string intrinsic_delaunay_laplacian(const SurfaceMesh& sm) {
    ddg::Triplets L;
    L.n = sm.number_of_vertices();
    for (const auto& f : intrinsic_faces(sm))
        for (int c = 0; c < 3; ++c)
            L.add_edge_weight(f.v[(c + 1) % 3], f.v[(c + 2) % 3], cot_at(f, c) / 2);
    return L.json();
}

static std::string intrinsic_delaunay_triangulation(const SurfaceMesh& sm) {
    auto faces = intrinsic_faces(sm);
    std::string F = ddg::list(faces, [](const IntrinsicFace& f) {
        return "[" + std::to_string(f.v[0]) + "," + std::to_string(f.v[1]) + "," +
               std::to_string(f.v[2]) + "]";
    });
    std::string l2 = ddg::list(faces, [](const IntrinsicFace& f) {
        std::vector<double> out;
        for (int c = 0; c < 3; ++c) {
            auto [x1, y1] = f.p[(c + 1) % 3];
            auto [x2, y2] = f.p[(c + 2) % 3];
            out.push_back((x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1));
        }
        return ddg::numbers(out);
    });
    return "{\"F\":" + F + ",\"l2\":" + l2 + "}";
}

int main(int argc, char** argv) {
    bool library_weights = false;
    for (int a = 1; a < argc; ++a) {
        std::string arg = argv[a];
        if (arg == "--weights=library") library_weights = true;
        else { std::cerr << "unknown argument " << arg << "\n"; return 2; }
    }
    ddg::Driver driver{
        library_weights ? "cgal-library-weights" : "cgal",
        {"cotan_laplacian", "area_gradient", "solve_dirichlet", "vertex_areas_voronoi",
         "vertex_areas_barycentric", "area", "intrinsic_delaunay_laplacian", "intrinsic_delaunay_triangulation"}};
    if (library_weights) {
        driver.methods = {"cotan_laplacian"};
        // the library's own factor, declared: with --expect-conventions a failure the
        // halved weights (this program without arguments) do not have is a convention
        driver.conventions = R"json({"follows": {"F-cgal-3": "Edge_cotangent_weight: 2x the notes' weight 1/2 (cot a + cot b)"}, "counterpart_arguments": []})json";
    }
    return driver.serve([&](const std::string& method, const ddg::Mesh& mesh) {
        SurfaceMesh sm = surface_mesh(mesh);
        if (method == "cotan_laplacian") return cotan_laplacian(sm, library_weights ? 1.0 : 0.5);
        if (method == "vertex_areas_voronoi")
            return corner_areas(sm, [](const Point& p, const Point& q, const Point& r) {
                return CGAL::Weights::mixed_voronoi_area(p, q, r);
            });
        if (method == "vertex_areas_barycentric")
            return corner_areas(sm, [](const Point& p, const Point& q, const Point& r) {
                return CGAL::Weights::barycentric_area(p, q, r);
            });
        if (method == "area") return ddg::num(PMP::area(sm));
        if (method == "area_gradient") return area_gradient(sm);
        if (method == "solve_dirichlet") return solve_dirichlet(sm, mesh);
        if (method == "intrinsic_delaunay_laplacian") {
            if (sm.number_of_faces() == 0) throw ddg::OutsideDomain("no faces");
            return intrinsic_delaunay_laplacian(sm);
        }
        if (method == "intrinsic_delaunay_triangulation") return intrinsic_delaunay_triangulation(sm);
        throw std::runtime_error("not implemented: " + method);
    });
}
