#!/usr/bin/env bash
# One evaluation per change: application code (the app, the CLI, the exporters, the benchmarks)
# evaluates a scene only through SceneDeformer::evaluate() / evaluateTakingPoints(), never by
# calling the steps evaluate() chooses from (update, updateGesture, finishGesture,
# finishGestureTakingPoints) by hand. Fails listing every such call.
#
#   check_single_evaluation.sh SOURCE_DIR
#
# Allowed: the deformer itself (scenes/src/scene_deformer.cpp, where evaluate() and deformScene
# live) and the Python module's SceneDeformer, whose update / updateGesture / finishGesture are
# the scripting interface to those steps (python/src/scenes_bindings.cpp). Tests call the steps to
# test them and are not searched. The pattern matches a call on any expression whose name holds
# "deform" (deformer_, d.deformer, job->deformer, deformed, ...); ffd::Deformer's own update()
# (an engine call, not a scene evaluation) is told apart by its sources: ffd/ and
# python/src/ffd_bindings.cpp are not searched, nor bench/ffd.
set -euo pipefail
root="${1:?usage: check_single_evaluation.sh SOURCE_DIR}"
cd "$root"
pattern='[A-Za-z_]*[Dd]eform[A-Za-z_]*[[:space:]]*(\.|->)[[:space:]]*(update|updateGesture|finishGesture|finishGestureTakingPoints)[[:space:]]*\('
found="$(grep -rnE --include='*.cpp' --include='*.h' --include='*.cc' "$pattern" \
           app scenes exporters meshio python/src bench/app bench/scenes bench/exporters bench/meshio 2>/dev/null |
         grep -vE '^(scenes/src/scene_deformer\.cpp|python/src/scenes_bindings\.cpp|python/src/ffd_bindings\.cpp):' |
         grep -vE '^[^:]+:[0-9]+:[[:space:]]*(//|///|\*)' || true)"
if [ -n "$found" ]; then
  echo "check_single_evaluation: these lines evaluate a scene by hand; mark the change (the model's own"
  echo "edits do) and let SceneDeformer::evaluate() run once where the operation ends:"
  echo "$found"
  exit 1
fi
echo "check_single_evaluation: no call of update/updateGesture/finishGesture outside the evaluator"
