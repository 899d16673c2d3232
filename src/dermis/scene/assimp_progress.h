// Assimp's progress reports passed on to a load stage, and Ctrl-C passed back to Assimp.
// Assimp ignores a progress handler's "stop" (Update returning false) while an importer
// reads: its OBJ reader reports each 16 MB block it streams and reads on. It does catch
// exceptions from inside an importer and return no scene (BaseImporter::ReadFile), so the
// handler throws StopReading once the stage is cancelled, and the caller, finding no
// scene and the stage cancelled, throws Interrupted.
#pragma once

#include <assimp/ProgressHandler.hpp>
#include <stdexcept>

#include "dermis/core/load_monitor.h"

namespace dermis {

struct StopReading : std::runtime_error {
  StopReading() : std::runtime_error("stopped (Ctrl-C)") {}
};

class AssimpStageProgress : public Assimp::ProgressHandler {
 public:
  explicit AssimpStageProgress(LoadStage& stage) : stage_(stage) {}
  // Reports `fraction` (Assimp: reading in [0, 0.5], post-processing in [0.5, 1]; < 0:
  // a question "go on?"); throws StopReading when the stage is cancelled.
  bool Update(float fraction) override {
    if (stage_.cancelled()) throw StopReading();
    if (fraction >= 0) stage_.try_update(fraction);
    return true;
  }

 private:
  LoadStage& stage_;
};

}  // namespace dermis
