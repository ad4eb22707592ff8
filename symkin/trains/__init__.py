"""Trains described in files: any planar gear train, its brake and clutch states, shift tables.

- :mod:`.file`: the TOML train file (its format is in the module's docstring and in
  ``docs/trains.md``), :func:`load_train`, and the ready-made files shipped with symkin
  (:func:`ready_made`: ``simple``, ``wolfrom``, ``simpson``, ``ravigneaux``,
  ``double-pinion``, ``ferguson``, the transmissions ``simpson-oneway``, ``hub-3speed``,
  ``power-split``, ``eight-speed``, ...);
- :mod:`.one_way`: one-way clutches (:class:`OneWay`) and which hold in each state;
- :mod:`.train`: :class:`Train` (a :class:`~symkin.model.Mechanism` with named states),
  :class:`State`, and the solved :class:`Shift` and :class:`ShiftTable`.

    >>> from symkin.trains import load_train
    >>> train = load_train("simple")
    >>> print(train.shift_table().text())   # doctest: +NORMALIZE_WHITESPACE
    simple planetary: 3 states, ratio = omega_input/omega_output
    state      input  output  brakes  clutches  ratio  float
    ---------  -----  ------  ------  --------  -----  -----
    low        S      C       R       -         4      4
    reverse    S      R       C       -         -3     -3
    overdrive  C      R       S       -         3/4    0.75
"""

from __future__ import annotations

from symkin.trains.file import READY_MADE, load_train, read_train, ready_made
from symkin.trains.one_way import Engagement, OneWay
from symkin.trains.train import Shift, ShiftTable, State, Train

__all__ = ["load_train", "read_train", "ready_made", "READY_MADE", "Train", "State", "Shift", "ShiftTable", "OneWay",
           "Engagement"]
