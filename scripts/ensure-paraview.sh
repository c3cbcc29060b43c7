#!/usr/bin/env bash
# Installs ParaView (pvbatch) and Xvfb from Debian's packages when they are missing (sourced by
# the test script): `scripts/render_views.py` runs under pvbatch, and its test renders off screen
# in an Xvfb display.
if ! command -v pvbatch >/dev/null 2>&1 || ! command -v Xvfb >/dev/null 2>&1; then
  SUDO=""
  if [ "$(id -u)" != "0" ]; then SUDO="sudo"; fi
  echo "installing ParaView and Xvfb (Debian packages)..." >&2
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq paraview xvfb >/dev/null
fi
