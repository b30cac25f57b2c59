// The in-process stock: the workpiece as the operations so far have left it, in the workpiece frame, through any
// number of setups (the part turned over between them).
//
// The model is the raw stock as Z-dexels (dexels.hpp) and, for each setup that has cut, its removal envelope: a
// height field in that setup's frame, lowered by the swept cutter of every move (material_removal.hpp). Within a
// setup all machining is 3-axis with the shank above the tip, so a program removes exactly the points at or above
// the lowest cutter bottom over them; a point p is material when it is in the raw stock and, for every setup s,
// (R_s p).z lies below envelope_s at (R_s p).xy. The dexels of that material (the raw stock clipped by every
// envelope) are kept up to date, so volumes and views read them directly; each envelope keeps its own setup's
// precision for the next program in that setup. The envelopes are sampled at their cells' centres; each setup's
// moves are kept too (swept_moves.hpp), so that a point anywhere is answered exactly (material_at): what the
// account of the material left on the part's faces measures with, walls and corners included.
#pragma once
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rosmill/geometry/mesh.hpp"
#include "rosmill/geometry/point_cloud.hpp"
#include "rosmill/geometry/setup_frame.hpp"
#include "rosmill/stock/dexels.hpp"
#include "rosmill/stock/height_field.hpp"
#include "rosmill/stock/material_removal.hpp"
#include "rosmill/stock/multi_axis_program.hpp"
#include "rosmill/stock/multi_axis_sweep.hpp"
#include "rosmill/stock/program.hpp"
#include "rosmill/stock/swept_moves.hpp"

namespace rosmill::core::stock {

// The top of material seen from a setup where a cell has none.
constexpr float kNoMaterial = -std::numeric_limits<float>::infinity();

// What removing a program did.
struct RemovalReport {
  size_t moves = 0;
  double removed_mm3 = 0;        // material the program removed
  size_t cut_cells = 0;          // cells of the setup's grid where a move went into material
  size_t rapid_cut_cells = 0;    // of them, cut by a rapid (G0): a collision
  uint32_t first_rapid_move = HeightField::kNoMove;  // index in the program's moves of the first rapid that cut
  uint32_t first_rapid_source = 0;                   // its G-code line or toolpath move number (0: none)
  double feed_mm = 0;            // length of the feed moves (lines and arcs)
  double air_feed_mm = 0;        // of it, moves that cut no material (air cutting)
  double seconds = 0;
  bool collided() const { return rapid_cut_cells > 0; }
  double air_cut_share() const { return feed_mm > 0 ? air_feed_mm / feed_mm : 0.0; }
};

class InProcessStock {
 public:
  // Raw stock: a box, a closed mesh (a casting), or a cloud scanned from above standing on the table at table_z.
  // `resolution` is the cell edge in mm; a grid of more than max_cells cells is refused (Error naming `where`, with
  // the memory it would take) before anything is allocated.
  static InProcessStock box(const Box3& box, double resolution, size_t max_cells = kMaxGridCells,
                            const std::string& where = "stock");
  static InProcessStock from_mesh(const Mesh& mesh, double resolution, size_t max_cells = kMaxGridCells,
                                  const std::string& where = "stock mesh");
  static InProcessStock from_cloud(const PointCloud& cloud, double table_z, double resolution, int fill_cells = 3,
                                   size_t max_cells = kMaxGridCells, const std::string& where = "stock cloud");

  // Removes what `program` (in the frame of `setup`) cuts; a rapid that cuts material is reported with its source.
  RemovalReport remove(const MachineProgram& program, const SetupFrame& setup = {},
                       const SimulationOptions& options = {});
  // Removes what a multi-axis program (workpiece frame, the tool axis turning along its moves) cuts with ball-end
  // mills: their flutes' sweep (multi_axis_sweep.hpp), its steps' chords within a micrometre of the tool's arcs, kept
  // for the exact point queries too. A flat or bull-nose tool is refused (Error naming the move); so is an axis that is
  // not a direction.
  RemovalReport remove(const MultiAxisProgram& program);

  // The top of material seen from a setup, per cell of the setup's grid (a grid over the stock turned into the
  // setup's frame, at the stock's resolution): kNoMaterial where a cell has none; `bottom` is the lowest material.
  HeightField view(const SetupFrame& setup = {}) const;
  // The grid of view(setup), without computing the view.
  GridSpec setup_grid(const SetupFrame& setup) const;
  // Material left above the design, per cell of view(setup): the stock's top minus the design's (the mesh in the
  // workpiece frame, turned into the setup's); NaN where there is no material.
  std::vector<float> material_above(const Mesh& design, const SetupFrame& setup = {}) const;
  // The bounds of the material left, in the setup's frame (each cell's square prism from its lowest to its highest
  // material turned); empty when nothing is left. What a fixture holds and a datum is found on.
  Box3 bounds_in(const SetupFrame& setup) const;
  // The corners of every cell's material prism (its lowest and highest material), workpiece frame: the material
  // turned any way reaches no farther than one of them.
  std::vector<Vec3> material_corners() const;
  // True when some material stands at or above z over the XY box [lo, hi] (the setup's frame).
  bool material_in(const Vec2& lo, const Vec2& hi, double z, const SetupFrame& setup = {}) const;

  // Exact point queries (workpiece frame), thread-safe: whether p lies in the raw stock (a box exactly; a mesh or a
  // scan as its dexel over p's cell), whether some setup's moves cut it away, and both: material.
  bool raw_at(const Vec3& p) const;
  bool removed_at(const Vec3& p) const;
  bool material_at(const Vec3& p) const { return raw_at(p) && !removed_at(p); }
  // Material at p farther than a few micrometres (the swept moves' near distance) from what was cut away: a sliver
  // thinner than twice that (the facets of a hole leave an end mill one at each corner) is not.
  bool solid_at(const Vec3& p) const { return raw_at(p) && !cut_near(p); }
  bool cut_near(const Vec3& p) const;
  double near_distance() const;
  // The largest t in [0, t_max] with p + t * direction still in the raw stock's box (0 when p is outside it): how
  // far a line can hold material at all.
  double raw_extent(const Vec3& p, const Vec3& direction, double t_max) const;

  double volume() const { return material_.volume(); }  // mm^3
  const Dexels& material() const { return material_; }   // what is left, in the workpiece frame
  const GridSpec& grid() const { return material_.grid; }
  size_t bytes() const;  // the model's memory
  size_t setups() const { return envelopes_.size(); }
  const MultiAxisSweep& multi_axis_sweep() const { return swept_; }  // what multi-axis programs cut

 private:
  friend class StockProbe;
  struct Envelope {
    SetupFrame setup;
    HeightField field;  // lowest cutter bottom per cell (+infinity where nothing passed)
    SweptMoves moves;   // every move that made it, for exact queries between the cells' centres
  };
  explicit InProcessStock(Dexels raw, std::optional<Box3> box = std::nullopt)
      : material_(raw), raw_(std::move(raw)), raw_box_(box) {}
  size_t envelope_index(const SetupFrame& setup) const;  // envelopes_.size() when the setup has none
  Envelope& envelope_of(const SetupFrame& setup);
  const Envelope* envelope_if(const SetupFrame& setup) const;
  Box3 turned_bounds(const SetupFrame& setup) const;
  double top_along(const SetupFrame& setup, double u, double v) const;
  double top_at(const SetupFrame& setup, const Envelope* env, const GridSpec& g, int i, int j) const;
  void clip(const Envelope& e);
  void clip_swept(size_t first_triangle, const MultiAxisProgram& program, std::vector<uint8_t>& moves_cut,
                  RemovalReport& r);

  Dexels material_;
  Dexels raw_;                    // the raw stock, as it was read
  std::optional<Box3> raw_box_;   // a box stock's own box (exact where its dexels round to their cells)
  std::vector<Envelope> envelopes_;
  MultiAxisSweep swept_;  // what multi-axis programs cut, in the workpiece frame
};

// The stock's exact point queries, many of them near one another (a line followed out from a face): each setup's
// moves that can cut within `radius` of a place are gathered once (SweptMoves::gather), and a query within that
// distance reads those alone; a query farther off gathers again around itself. It keeps its lists from query to
// query: one per thread, over a stock that no longer changes.
class StockProbe {
 public:
  StockProbe(const InProcessStock& stock, double radius);
  bool removed_at(const Vec3& p);
  bool cut_near(const Vec3& p);
  bool material_at(const Vec3& p) { return stock_.raw_at(p) && !removed_at(p); }
  bool solid_at(const Vec3& p) { return stock_.raw_at(p) && !cut_near(p); }

 private:
  void aim(const Vec3& p);
  const InProcessStock& stock_;
  double radius_;
  Vec3 centre_ = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  std::vector<std::vector<uint32_t>> moves_;  // per envelope: the moves that can cut near the centre
};

}  // namespace rosmill::core::stock
