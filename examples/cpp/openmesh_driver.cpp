// OpenMesh 9 (Debian libopenmesh-dev) checked by ddg-oracle through the executable
// protocol (docs/protocol.md).  Built by build.sh when CMake finds OpenMesh.
//
//   ddg-oracle check --impl 'exec:examples/cpp/build/openmesh_driver'
//   ddg-oracle check --impl 'exec:examples/cpp/build/openmesh_driver --weights=library'
//
// What is called, on a TriMesh_ArrayKernelT with double points (OpenMesh's default
// points are float; double makes the comparison with float64 bounds fair):
//   euler_characteristic  n_vertices() - n_edges() + n_faces()
//   boundary_loops        the boundary halfedges, followed with next_halfedge_handle
//   genus                 (2 - chi - k) / 2: OpenMesh has no genus; a TriMesh is
//                         orientable, so this is R1.6 solved for g
//   area                  the sum of calc_face_area
//   cotan_laplacian       Smoother::JacobiLaplaceSmootherT's edge weights after
//                         initialize(Normal, C0) (its CotWeighting: cot a + cot b,
//                         2x the notes'), halved (--weights=library: as OpenMesh gives it)
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Smoother/JacobiLaplaceSmootherT.hh>

#include "ddg_protocol.hpp"

struct DoubleTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

static void build(const ddg::Mesh& mesh, TriMesh& tm) {
    for (const auto& p : mesh.V) tm.add_vertex(TriMesh::Point(p[0], p[1], p[2]));
    for (size_t f = 0; f < mesh.F.size(); ++f) {
        const auto& t = mesh.F[f];
        for (long i : t)
            if (i < 0 || size_t(i) >= mesh.V.size())
                throw std::runtime_error("face " + std::to_string(f) + ": index out of range");
        auto fh = tm.add_face(TriMesh::VertexHandle(int(t[0])), TriMesh::VertexHandle(int(t[1])),
                              TriMesh::VertexHandle(int(t[2])));
        // a halfedge mesh holds oriented 2-manifolds only (OpenMesh says why on stderr)
        if (!fh.is_valid())
            throw ddg::OutsideDomain("TriMesh::add_face refused face " + std::to_string(f) +
                                     " (non-orientable or non-manifold)");
    }
}

// The weights are protected members of LaplaceSmootherT; initialize() computes them.
// JacobiLaplaceSmootherT is the smoother users instantiate (LaplaceSmootherT is abstract).
struct CotanWeights : OpenMesh::Smoother::JacobiLaplaceSmootherT<TriMesh> {
    using Base = OpenMesh::Smoother::JacobiLaplaceSmootherT<TriMesh>;
    explicit CotanWeights(TriMesh& tm) : Base(tm) { initialize(Base::Normal, Base::C0); }
    using Base::weight;
};

static std::vector<std::vector<int>> boundary_loops(const TriMesh& tm) {
    std::vector<std::vector<int>> loops;
    std::vector<bool> seen(tm.n_halfedges(), false);
    for (auto h : tm.halfedges()) {
        if (!tm.is_boundary(h) || seen[h.idx()]) continue;
        std::vector<int> loop;
        for (auto g = h; !seen[g.idx()]; g = tm.next_halfedge_handle(g)) {
            seen[g.idx()] = true;
            loop.push_back(tm.from_vertex_handle(g).idx());
        }
        loops.push_back(loop);
    }
    return loops;
}

int main(int argc, char** argv) {
    bool library_weights = false;
    for (int a = 1; a < argc; ++a) {
        std::string arg = argv[a];
        if (arg == "--weights=library") library_weights = true;
        else { std::cerr << "unknown argument " << arg << "\n"; return 2; }
    }
    ddg::Driver driver{library_weights ? "openmesh-library-weights" : "openmesh",
                       {"euler_characteristic", "boundary_loops", "genus", "area",
                        "cotan_laplacian"}};
    if (library_weights) {
        driver.methods = {"cotan_laplacian"};
        // the library's own factor, declared: with --expect-conventions a failure the
        // halved weights (this program without arguments) do not have is a convention
        driver.conventions = R"json({"follows": {"F-openmesh-2": "LaplaceSmootherT CotWeighting: cot a + cot b, 2x the notes' weight"}, "counterpart_arguments": []})json";
    }
    return driver.serve([&](const std::string& method, const ddg::Mesh& mesh) -> std::string {
        TriMesh tm;
        build(mesh, tm);
        long chi = long(tm.n_vertices()) - long(tm.n_edges()) + long(tm.n_faces());
        if (method == "euler_characteristic") return std::to_string(chi);
        if (method == "boundary_loops")
            return ddg::list(boundary_loops(tm), [](const std::vector<int>& loop) {
                return ddg::list(loop, [](int v) { return std::to_string(v); });
            });
        if (method == "genus") {
            // the surface's chi: a vertex used by no face is a point beside it
            long surface_chi = chi;
            for (auto v : tm.vertices())
                if (tm.is_isolated(v)) --surface_chi;
            long twice = 2 - surface_chi - long(boundary_loops(tm).size());
            if (twice % 2) throw std::runtime_error("2 - chi - k is odd: not one surface");
            return std::to_string(twice / 2);
        }
        if (method == "area") {
            double A = 0;
            for (auto f : tm.faces()) A += tm.calc_face_area(f);
            return ddg::num(A);
        }
        if (method == "cotan_laplacian") {
            CotanWeights w(tm);
            ddg::Triplets L;
            L.n = tm.n_vertices();
            for (auto e : tm.edges()) {
                auto h = tm.halfedge_handle(e, 0);
                L.add_edge_weight(tm.from_vertex_handle(h).idx(), tm.to_vertex_handle(h).idx(),
                                  (library_weights ? 1.0 : 0.5) * w.weight(e));
            }
            return L.json();
        }
        throw std::runtime_error("not implemented: " + method);
    });
}
