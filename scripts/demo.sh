#!/usr/bin/env bash
# The main job: builds mb_kinematics and shows it at work on the human body model.
source "$(dirname "$0")/common.sh"
mbk_install_deps
mbk_build
model="$MBK_SRC/config/human_body.yaml"
echo "== mbk tables --model config/human_body.yaml"
mbk tables --model "$model"
echo "== mbk eval --model config/human_body.yaml --state config/human_body_state.json"
mbk eval --model "$model" --state "$MBK_SRC/config/human_body_state.json"
