// model/vectors/scene_dump.hpp — transaction vectors: a whole draw dumped at every stage boundary
// of the raster unit through the chain's taps (model/unit/chain.hpp), read back, and re-stepped
// stage by stage (docs/vectors.md, "Transaction vectors").
//
// For every stage S of the chain (convert, clip, recip, viewport, setup, traverse, interp, depth,
// divide, then the line path's line_convert, line_clip, line_recip, line_viewport, line_setup,
// line, line_interp, line_depth, line_divide) two vector files in the one-word-per-line hex
// format of model/vectors/vectors.hpp:
//   S.in.hex   one line per record S received:  txn, n_out[, ctx], then the In record's fields
//   S.out.hex  one line per record S emitted:   txn, seq, last, then the Out record's fields
// txn numbers S's inputs from 0 in stream order; an output carries the txn of the input it came
// from, its index seq among that input's outputs and last = 1 on the final one; n_out is the
// number of outputs of the input (0 when the stage emitted nothing: a rejected, culled or
// depth-failed record). So 1 → 0..n stages (clipper, traversal, interpolators) need no
// special case: a testbench drives S.in rows and expects, per txn, exactly n_out S.out rows.
// ctx (interp and line_interp only) is the line (from 0) of setup.out (line_setup.out) holding
// the primitive's equations, the per-primitive context the interpolators latch. The field lists
// come from the records' visit() (model/vectors/record_vectors.hpp): nothing is hand-written, and
// a value that does not fit its declared width stops the dump with an error naming the stage and
// field. Line segments are drawn after the triangles with their own draw state (depth function,
// test, write), so their depth test and divider have files of their own (line_depth,
// line_divide), re-stepped on the depth buffer the triangles' depth stage left.
// Beside them, scene.json: the configuration, the draw state (the DrawState record), the line
// draw state, the files
// with their counts, and the unit's statistics.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {

// scene.json "format" / "format_version": bumped when the transaction layout rules change.
inline constexpr const char* kSceneVectorFormatName = "fxraster-scene-vectors";
// Version 2: the line path's stages (line_convert … line_divide) and scene.json's line_segments
// and line_draw_state.
inline constexpr int kSceneVectorFormatVersion = 2;
// Transaction header fields: ids and counts are unsigned 32 bits (a dump with more records per
// stage is refused with an error).
inline constexpr int kTxnIdBits = 32;
inline constexpr int kTxnCountBits = 32;
// Header fields: in files txn, n_out (+ ctx for interp, line_interp); out files txn, seq, last (1 bit).
inline constexpr int kTxnInHeaderFields = 2;
inline constexpr int kTxnCtxHeaderFields = 3;
inline constexpr int kTxnOutHeaderFields = 3;

// The stages in chain order (the names are the stages' kName).
const std::vector<std::string>& scene_dump_stages();

struct SceneDumpFile {
  std::string stage, side;  // side: "in" or "out"
  std::string hex;          // file name inside the dump folder
  uint64_t rows = 0;
  int word_bits = 0;
};

struct SceneDump {
  std::vector<SceneDumpFile> files;
  RasterStats stats;
};

// Contract: runs the raster unit on `tris` with `st` (fragments streamed, as run_raster_unit)
// and writes every stage boundary into folder `dir` (created; replaced when it holds only a
// previous dump's files, otherwise an error). Written into a temporary folder beside `dir` and
// renamed at the end: a failed dump leaves no partial folder. Deterministic: the same inputs give
// byte-identical files. Throws ConfigError.
SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const std::string& dir, const std::string& scene_name);
// The same with line segments: the triangles, then `lines` through the line path with `line_st`
// (run_raster_unit_to of model/unit/line_chain.hpp), segment k primitive tris.size() + k. The
// line stages' files are written (empty) when there are no segments. line_st must have st's
// number of varyings (one record shape); otherwise ConfigError.
SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const DrawState& line_st, const std::vector<ClipLine>& lines, const std::string& dir,
                             const std::string& scene_name);
// The same, writing only the files of `stages` (stage names of scene_dump_stages(); empty: every
// stage). The draw runs whole; scene.json's "files" lists what was written, and readers take the
// stages present from it (restep_scene_vectors re-steps those, load_scene_stage refuses another).
// A stage whose re-step needs another stage's file needs that stage too: interp needs setup
// (ctx), line_interp line_setup, line_depth depth (the buffer the triangles left). Unknown or
// repeated names, or a missing prerequisite: ConfigError. (The committed back-end vectors,
// docs/vectors.md, are such subsets: fewer manifests.)
SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const DrawState& line_st, const std::vector<ClipLine>& lines, const std::string& dir,
                             const std::string& scene_name, const std::vector<std::string>& stages);

// Re-reading and re-stepping a dump: every file is read and validated (manifest format, layout
// equal to the records' layout at the dump's configuration, hex lines, transaction ids and
// counts consistent between S.in and S.out), then every stage is stepped again on its S.in
// records alone — in order, the depth stage on a freshly cleared buffer, the interpolators with
// the context from setup.out — and its outputs compared with S.out field by field.
struct RestepStage {
  std::string stage;
  uint64_t in_rows = 0, out_rows = 0, mismatches = 0;
};
struct RestepReport {
  std::vector<RestepStage> stages;
  std::vector<std::string> first;  // up to max_report mismatch descriptions (file:line, field)
  uint64_t mismatches() const {
    uint64_t n = 0;
    for (const auto& s : stages) n += s.mismatches;
    return n;
  }
};
RestepReport restep_scene_vectors(const std::string& dir, size_t max_report = 20);

}  // namespace fxr

namespace fxr {

// One stage's two files of a dump, read and validated as restep_scene_vectors does (manifests
// against the records' layouts at the dump's configuration, transaction headers consistent): what
// an RTL testbench drives (in) and expects (out). Rows are flat: row r, field f at
// data[r·lay.size() + f]; the record's fields follow the header columns (in: txn, n_out[, ctx];
// out: txn, seq, last).
struct SceneStageFile {
  std::string path;  // the hex file (error messages: path:line, line = row + 1)
  VecLayout lay;
  size_t header = 0;  // header columns before the record's fields
  uint64_t rows = 0;
  std::vector<vec_word> data;
  VecRow row(uint64_t r) const {
    const size_t n = lay.size();
    return VecRow(data.begin() + (ptrdiff_t)(r * n), data.begin() + (ptrdiff_t)((r + 1) * n));
  }
};
struct SceneStageVectors {
  std::string stage;
  Config cfg;
  int num_varyings = 0;
  SceneStageFile in, out;
};
// The draw state of a dump (scene.json "draw_state", or "line_draw_state" with lines = true),
// read and range-checked by the same reader as load_scene_stage. Throws ConfigError naming the file.
DrawState load_scene_draw_state(const std::string& dir, bool lines = false);
// The stages whose files a dump holds (scene.json "files"), in chain order.
std::vector<std::string> scene_dump_stages_present(const std::string& dir);
// Throws ConfigError naming the file (and line / field) on any inconsistency, or when the dump
// does not hold the stage.
SceneStageVectors load_scene_stage(const std::string& dir, const std::string& stage);

}  // namespace fxr
