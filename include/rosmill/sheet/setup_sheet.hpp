// The setup sheet of a job: one self-contained HTML file (its pictures inline as PNG data) that a person prints
// and takes to the machine. Per setup, in machining order: the face the part stands on, the fixture and how it
// holds the stock, the datum and the work offset (G54..G59, with where it lies on the machine), the tools with
// their stick-out, the operations with their estimated times, the program's file name, and a picture of the part
// in its fixture in that setup's orientation with the setup's toolpaths, one colour per operation. Pictures are
// drawn off-screen with cairo (no display needed): the part's triangles and the fixture's boxes shaded by their
// normals and painted far to near, the toolpaths as lines over them.
#pragma once
#include <string>
#include <vector>

#include "rosmill/fixture/fixture.hpp"
#include "rosmill/geometry/mesh.hpp"
#include "rosmill/job/run_job.hpp"
#include "rosmill/toolpath/job.hpp"

namespace rosmill::core::sheet {

struct SheetJob {
  std::string title;                  // the job file
  const job::JobReport* report = nullptr;
  const Mesh* part = nullptr;         // the design, workpiece frame
  std::vector<Job> toolpaths;         // per operation of the report, in its setup's frame
};

// The picture of one setup: the part (already in the setup's frame), the fixture (same frame) and each operation's
// toolpaths in its own colour, seen from in front, to the right and above, as PNG bytes `width` x `height`.
std::vector<unsigned char> setup_picture_png(const Mesh& part_in_setup, const fixture::Fixture& fixture,
                                             const std::vector<const Job*>& operations, int width, int height);

// The colour of operation k of a setup in its picture and its legend: "#rrggbb".
std::string operation_colour(size_t k);

std::string setup_sheet_html(const SheetJob& job);
// Writes the sheet; throws Error naming the file when it cannot.
void write_setup_sheet(const std::string& path, const SheetJob& job);

}  // namespace rosmill::core::sheet
