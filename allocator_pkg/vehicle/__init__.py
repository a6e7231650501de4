"""The vehicle as configuration: frozen types of actuators, rotations, weights and settings
(``config``), angle helpers (``angles``), the node's own settings (``node_settings``) and the
FRD/FLU frame conversions (``frames``). Nothing here computes an allocation."""
