"""The vocabulary every layer and every mechanism shares: findings, parts, printers and materials,
rigid transforms, and the Kit and Mechanism protocols. numpy only; imports nothing of partgen."""
