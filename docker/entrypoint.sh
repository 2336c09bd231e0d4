#!/usr/bin/env bash
set -e
source /ws/devel/setup.bash
exec "$@"
